#include "design/unclosed_bracket.hpp"

#include <algorithm>
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
  std::size_t i = text.starts_with("\xEF\xBB\xBF") ? 3 : 0; // a byte-order mark, which the parser skips
  while (i < text.size() && !reached()) {
    const std::string_view rest = text.substr(i);
    if (rest.starts_with("\"\"\"") || rest.starts_with("'''")) {
      // A multi-line string: in a basic one (""") a backslash escapes the next character; it closes
      // at three quotes, and up to two more right after them are its own last characters.
      const char quote = rest.front();
      std::size_t k = 3;
      while (k < rest.size() && !rest.substr(k).starts_with(rest.substr(0, 3)))
        k += quote == '"' && rest[k] == '\\' ? 2 : 1;
      k = std::min(k + 3, rest.size());
      for (int extra = 0; extra < 2 && k < rest.size() && rest[k] == quote; ++extra) ++k;
      advance(i, k);
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
