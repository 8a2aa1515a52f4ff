#include "make/unset_values.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

#include "design/undeclared_value.hpp"

namespace fibermold {

namespace {

bool word_character(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

/// Whether `c` starts a character of UTF-8 text (is not one of its continuation bytes).
bool starts_character(char c) { return (static_cast<unsigned char>(c) & 0xC0) != 0x80; }

/// "line 27: "…reaching nan mm beyond the skin…"": the line of `at` and up to 40 bytes of it either
/// side, cut between characters.
std::string where(std::string_view text, std::size_t at, std::size_t length)
{
  const std::size_t line = 1 + static_cast<std::size_t>(std::count(text.begin(), text.begin() + at, '\n'));
  const std::size_t line_start = text.rfind('\n', at) == std::string_view::npos ? 0 : text.rfind('\n', at) + 1;
  const std::size_t line_end = std::min(text.find('\n', at), text.size());
  std::size_t from = std::max(line_start, at > 40 ? at - 40 : 0), to = std::min(line_end, at + length + 40);
  while (from > line_start && !starts_character(text[from])) --from;
  while (to < line_end && !starts_character(text[to])) ++to;
  return fmt::format("line {}: \"{}{}{}\"", line, from > line_start ? "…" : "", text.substr(from, to - from),
                     to < line_end ? "…" : "");
}

} // namespace

std::optional<std::string> unset_value(std::string_view text, bool json_null)
{
  // A design value the stage read without declaring it (undeclared_value.hpp): its text or its int.
  const std::string undeclared = undeclared_text(""), undeclared_int = std::to_string(kUndeclaredInt);
  for (const std::string_view marker :
       {std::string_view(undeclared).substr(0, undeclared.size() - 1), std::string_view(undeclared_int)})
    if (const std::size_t at = text.find(marker); at != std::string_view::npos) return where(text, at, marker.size());
  static constexpr std::array<std::string_view, 3> kWords{"nan", "inf", "null"};
  for (std::size_t w = 0; w < (json_null ? 3u : 2u); ++w)
    for (std::size_t at = text.find(kWords[w]); at != std::string_view::npos; at = text.find(kWords[w], at + 1)) {
      const std::size_t end = at + kWords[w].size();
      if ((at == 0 || !word_character(text[at - 1])) && (end == text.size() || !word_character(text[end])))
        return where(text, at, kWords[w].size());
    }
  return std::nullopt;
}

std::optional<std::string> unset_value_in(const std::filesystem::path& file)
{
  const std::string ext = file.extension().string();
  static constexpr std::array<std::string_view, 6> kText{".json", ".txt", ".html", ".csv", ".vtu", ".obj"};
  if (std::find(kText.begin(), kText.end(), ext) == kText.end()) return std::nullopt;
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return unset_value(text.str(), ext == ".json");
}

} // namespace fibermold
