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

/// Whether [at, end) lies in a run of 40 or more base64 characters (report.html's meshes): encoded data,
/// whose letters spell words by chance (about once in 10⁹ bytes), not text.
bool in_encoded_run(std::string_view text, std::size_t at, std::size_t end)
{
  const auto encoded = [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '+' || c == '/' || c == '=';
  };
  std::size_t from = at, to = end;
  while (from > 0 && encoded(text[from - 1])) --from;
  while (to < text.size() && encoded(text[to])) ++to;
  return to - from >= 40;
}

/// Whether the word at `at` is inside one of `own` (a name or path the user chose: "/afs/inf.ed.ac.uk/…",
/// a fiber named "inf-1") where it stands in `text`.
bool in_own_text(std::string_view text, std::size_t at, std::string_view word, const std::vector<std::string>& own)
{
  for (const std::string& s : own)
    for (std::size_t k = s.find(word); k != std::string::npos; k = s.find(word, k + 1))
      if (k <= at && text.substr(at - k, s.size()) == s) return true;
  return false;
}

} // namespace

std::optional<std::string> unset_value(std::string_view text, bool json_null, const std::vector<std::string>& own)
{
  // A design value the stage read without declaring it (undeclared_value.hpp): its text (report.html escapes
  // its '<') or its int; then what fmt prints for a NaN or an infinity, and nlohmann for a NaN in JSON.
  const std::string undeclared = undeclared_text(""), undeclared_int = std::to_string(kUndeclaredInt);
  const std::string marker = undeclared.substr(0, undeclared.size() - 1), escaped = "&lt;" + marker.substr(1);
  const std::array<std::pair<std::string_view, bool>, 6> patterns{
      {{marker, false}, {escaped, false}, {undeclared_int, false}, {"nan", true}, {"inf", true}, {"null", true}}};
  for (const auto& [pattern, word] : patterns) {
    if (pattern == "null" && !json_null) continue;
    for (std::size_t at = text.find(pattern); at != std::string_view::npos; at = text.find(pattern, at + 1)) {
      const std::size_t end = at + pattern.size();
      if (word && ((at > 0 && word_character(text[at - 1])) || (end < text.size() && word_character(text[end]))))
        continue;
      if (word && (in_encoded_run(text, at, end) || in_own_text(text, at, pattern, own))) continue;
      return where(text, at, pattern.size());
    }
  }
  return std::nullopt;
}

std::optional<std::string> unset_value_in(const std::filesystem::path& file, const std::vector<std::string>& own)
{
  const std::string ext = file.extension().string();
  static constexpr std::array<std::string_view, 6> kText{".json", ".txt", ".html", ".csv", ".vtu", ".obj"};
  if (std::find(kText.begin(), kText.end(), ext) == kText.end()) return std::nullopt;
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return unset_value(text.str(), ext == ".json", own);
}

std::vector<std::string> own_text(const Design& d, const std::filesystem::path& build_dir)
{
  std::vector<std::string> out{d.design.name, build_dir.string(), std::filesystem::absolute(build_dir).string()};
  for (const std::filesystem::path& p : {d.file, d.design.surface}) {
    out.push_back(p.string());
    out.push_back(p.filename().string());
    out.push_back(p.parent_path().string());
  }
  for (const Fiber& f : d.fibers) out.push_back(f.name);
  for (const TrackingCurve& c : d.tracking_curves) out.push_back(c.name);
  for (const FixedRegion& f : d.fixed) out.push_back(f.name);
  for (const Target& t : d.targets) {
    out.push_back(t.name);
    out.push_back(t.surface.string());
  }
  std::erase_if(out, [](const std::string& s) { return s.empty(); });
  return out;
}

} // namespace fibermold
