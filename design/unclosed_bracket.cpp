#include "design/unclosed_bracket.hpp"

#include <vector>

namespace fibermold {

std::optional<OpenBracket> unclosed_bracket(std::string_view text, TextPlace before)
{
  std::vector<OpenBracket> open;
  TextPlace at{1, 1};
  const auto reached = [&] { return at.line > before.line || (at.line == before.line && at.column >= before.column); };
  const auto advance = [&](std::size_t& i, std::size_t n) {
    for (std::size_t end = i + n; i < end && i < text.size(); ++i) {
      if (text[i] == '\n') {
        ++at.line;
        at.column = 1;
      } else if ((static_cast<unsigned char>(text[i]) & 0xC0) != 0x80) { // a UTF-8 character's first byte
        ++at.column;
      }
    }
  };
  std::size_t i = 0;
  while (i < text.size() && !reached()) {
    const std::string_view rest = text.substr(i);
    if (rest.starts_with("\"\"\"") || rest.starts_with("'''")) { // a multi-line string, to its closing quotes
      const std::string_view quotes = rest.substr(0, 3);
      const std::size_t close = rest.find(quotes, 3);
      advance(i, close == std::string_view::npos ? rest.size() : close + 3);
    } else if (rest.front() == '"' || rest.front() == '\'') { // a string on one line; "\"" escapes a quote
      std::size_t k = 1;
      while (k < rest.size() && rest[k] != rest.front() && rest[k] != '\n')
        k += rest.front() == '"' && rest[k] == '\\' ? 2 : 1;
      advance(i, k + 1);
    } else if (rest.front() == '#') { // a comment, to the end of its line
      const std::size_t end = rest.find('\n');
      advance(i, end == std::string_view::npos ? rest.size() : end);
    } else {
      if (rest.front() == '[' || rest.front() == '{') open.push_back({at, rest.front()});
      if ((rest.front() == ']' || rest.front() == '}') && !open.empty()) open.pop_back();
      advance(i, 1);
    }
  }
  if (open.empty()) return std::nullopt;
  return open.back();
}

} // namespace fibermold
