#include "core/wrapped_text.hpp"

#include <algorithm>
#include <sstream>

namespace fibermold {

std::string wrapped(const std::string& text, const std::string& first, const std::string& rest)
{
  constexpr std::size_t kLineWidth = 100;
  const auto width = [](const std::string& s) {
    return static_cast<std::size_t>(std::count_if(s.begin(), s.end(), [](char c) { return (c & 0xC0) != 0x80; }));
  };
  std::string out, line = first;
  std::istringstream words(text);
  bool empty = true;
  for (std::string word; words >> word;) {
    if (!empty && width(line) + 1 + width(word) > kLineWidth) {
      out += line + "\n";
      line = rest;
      empty = true;
    }
    line += (empty ? "" : " ") + word;
    empty = false;
  }
  return out + line + "\n";
}

} // namespace fibermold
