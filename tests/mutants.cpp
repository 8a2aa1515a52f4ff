#include "mutants.hpp"

#include <algorithm>
#include <cstring>
#include <limits>
#include <regex>

namespace fibermold::test {

namespace {

/// Knuth's MMIX LCG; the high bits are the good ones.
class Lcg {
public:
  explicit Lcg(std::uint64_t seed) : state_(seed * 2862933555777941757ULL + 3037000493ULL) {}
  std::uint64_t next()
  {
    state_ = state_ * 6364136223846793005ULL + 1442695040888963407ULL;
    return state_ >> 11;
  }
  std::size_t below(std::size_t n) { return n == 0 ? 0 : static_cast<std::size_t>(next() % n); }
  template <typename T> const T& pick(const std::vector<T>& items) { return items[below(items.size())]; }

private:
  std::uint64_t state_;
};

std::vector<std::string> lines_of(const std::string& text)
{
  std::vector<std::string> lines;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t end = text.find('\n', start);
    lines.push_back(text.substr(start, end == std::string::npos ? std::string::npos : end - start));
    if (end == std::string::npos) break;
    start = end + 1;
  }
  return lines;
}

std::string joined(const std::vector<std::string>& lines)
{
  std::string text;
  for (std::size_t k = 0; k < lines.size(); ++k) text += lines[k] + (k + 1 < lines.size() ? "\n" : "");
  return text;
}

/// Values a number may become: the ends of double and int64, non-numbers, other types.
const std::vector<std::string> kNumbers = {"0",
                                           "-1",
                                           "1e308",
                                           "-1e308",
                                           "5e-324",
                                           "1e-300",
                                           "2147483647",
                                           "-2147483648",
                                           "9223372036854775807",
                                           "-9223372036854775808",
                                           "nan",
                                           "inf",
                                           "-inf",
                                           "1e9",
                                           "1e-9",
                                           "\"3\"",
                                           "true",
                                           "[1, 2, 3]",
                                           "{ a = 1 }",
                                           "0.5",
                                           "-0.0",
                                           "1e15",
                                           "4294967296"};

/// One mutation of a design text.
std::string mutate_design(const std::string& text, Lcg& rng, std::string& what)
{
  std::vector<std::string> lines = lines_of(text);
  const std::size_t l = rng.below(lines.size());
  std::string& line = lines[l];
  const auto at = " at line " + std::to_string(l + 1);
  switch (rng.below(9)) {
  case 0:
  case 1:
  case 2: { // a number literal becomes another value
    static const std::regex number(R"((^|[=\[, ])(-?[0-9][0-9.e+-]*))");
    std::vector<std::smatch> found;
    for (auto it = std::sregex_iterator(line.begin(), line.end(), number); it != std::sregex_iterator(); ++it)
      found.push_back(*it);
    if (found.empty()) break;
    const std::smatch& m = found[rng.below(found.size())];
    const std::string by = rng.pick(kNumbers);
    what += "number " + m[2].str() + " → " + by + at + "; ";
    line.replace(static_cast<std::size_t>(m.position(2)), static_cast<std::size_t>(m.length(2)), by);
    return joined(lines);
  }
  case 3:
    what += "deleted line " + std::to_string(l + 1) + "; ";
    lines.erase(lines.begin() + static_cast<std::ptrdiff_t>(l));
    return joined(lines);
  case 4:
    what += "doubled line " + std::to_string(l + 1) + "; ";
    lines.insert(lines.begin() + static_cast<std::ptrdiff_t>(l), line);
    return joined(lines);
  case 5: { // a string value becomes empty, huge, NUL-bearing, or a path out of the folder
    const auto q = line.find('"');
    const auto r = q == std::string::npos ? q : line.find('"', q + 1);
    if (r == std::string::npos) break;
    const std::vector<std::string> strings = {
        "", std::string(5000, 'a'), "a\\u0000b", "../../../../etc/passwd", "é✓ \\t", ".hidden"};
    const std::string& by = rng.pick(strings);
    what += "string → \"" + by.substr(0, 20) + "\"" + at + "; ";
    line.replace(q + 1, r - q - 1, by);
    return joined(lines);
  }
  case 6: { // a key misspelt
    const auto eq = line.find('=');
    if (eq == std::string::npos || eq < 2) break;
    const std::size_t k = rng.below(eq - 1);
    what += "misspelt key" + at + "; ";
    line[k] = static_cast<char>('a' + rng.below(26));
    return joined(lines);
  }
  case 7: { // a line of garbage
    const std::vector<std::string> garbage = {"[[",
                                              "= 3",
                                              "x = ",
                                              "[mold",
                                              "[mold]\nwall = 2",
                                              "\x01\x02",
                                              "key = \"unterminated",
                                              "[[fiber]]",
                                              "[[target]]\nname = \"t\""};
    const std::string& by = rng.pick(garbage);
    what += "inserted garbage" + at + "; ";
    lines.insert(lines.begin() + static_cast<std::ptrdiff_t>(l), by);
    return joined(lines);
  }
  default: { // cut short
    const std::size_t cut = rng.below(text.size());
    what += "cut at byte " + std::to_string(cut) + "; ";
    return text.substr(0, cut);
  }
  }
  what += "unchanged; ";
  return text;
}

bool binary_stl(const std::string& stl)
{
  if (stl.size() < 84) return false;
  std::uint32_t n = 0;
  std::memcpy(&n, stl.data() + 80, 4);
  return stl.size() == 84 + 50 * static_cast<std::size_t>(n);
}

float get_float(const std::string& s, std::size_t at)
{
  float v = 0;
  std::memcpy(&v, s.data() + at, 4);
  return v;
}
void set_float(std::string& s, std::size_t at, float v) { std::memcpy(s.data() + at, &v, 4); }

/// One mutation of a binary STL.
std::string mutate_binary_stl(std::string stl, Lcg& rng, std::string& what)
{
  std::uint32_t n = 0;
  std::memcpy(&n, stl.data() + 80, 4);
  const std::size_t t = rng.below(n), record = 84 + 50 * t;
  const std::vector<float> values = {
      std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity(), 3.4e38F, 1e-38F, -1e30F, 0.0F};
  switch (rng.below(9)) {
  case 0: { // one coordinate becomes extreme
    const float v = rng.pick(values);
    what = "a coordinate of triangle " + std::to_string(t) + " → " + std::to_string(v);
    set_float(stl, record + 12 + 4 * rng.below(9), v);
    return stl;
  }
  case 1: { // every coordinate scaled
    const std::vector<float> scales = {1e-30F, 1e-6F, 1e6F, 1e30F, -1.0F};
    const float k = rng.pick(scales);
    what = "every coordinate × " + std::to_string(k);
    for (std::uint32_t f = 0; f < n; ++f)
      for (int c = 0; c < 9; ++c)
        set_float(stl, 84 + 50 * f + 12 + 4 * c, get_float(stl, 84 + 50 * f + 12 + 4 * c) * k);
    return stl;
  }
  case 2: // a triangle flipped
    what = "triangle " + std::to_string(t) + " flipped";
    for (int c = 0; c < 3; ++c) {
      const float a = get_float(stl, record + 24 + 4 * c), b = get_float(stl, record + 36 + 4 * c);
      set_float(stl, record + 24 + 4 * c, b);
      set_float(stl, record + 36 + 4 * c, a);
    }
    return stl;
  case 3: { // a triangle lost (count kept right)
    what = "triangle " + std::to_string(t) + " removed";
    stl.erase(record, 50);
    const std::uint32_t m = n - 1;
    std::memcpy(stl.data() + 80, &m, 4);
    return stl;
  }
  case 4: { // a triangle doubled
    what = "triangle " + std::to_string(t) + " doubled";
    stl.insert(record, stl.substr(record, 50));
    const std::uint32_t m = n + 1;
    std::memcpy(stl.data() + 80, &m, 4);
    return stl;
  }
  case 5: { // the count lies
    const std::vector<std::uint32_t> counts = {0, n + 1, n * 1000, 0xFFFFFFFFu};
    const std::uint32_t m = rng.pick(counts);
    what = "triangle count " + std::to_string(n) + " → " + std::to_string(m);
    std::memcpy(stl.data() + 80, &m, 4);
    return stl;
  }
  case 6: { // cut short
    const std::size_t cut = rng.below(stl.size());
    what = "cut at byte " + std::to_string(cut);
    return stl.substr(0, cut);
  }
  case 7: { // a vertex moved into the body (a dent, or a self-intersection)
    what = "triangle " + std::to_string(t) + "'s first vertex pulled through the body";
    for (int c = 0; c < 3; ++c) set_float(stl, record + 12 + 4 * c, -get_float(stl, record + 12 + 4 * c));
    return stl;
  }
  default: { // noise over part of it
    const std::size_t from = rng.below(stl.size()), to = std::min(stl.size(), from + 1 + rng.below(200));
    what = "noise over bytes " + std::to_string(from) + "–" + std::to_string(to);
    for (std::size_t k = from; k < to; ++k) stl[k] = static_cast<char>(rng.next() & 0xFF);
    return stl;
  }
  }
}

} // namespace

std::vector<Mutant> design_mutants(const std::string& design, int count, std::uint64_t seed)
{
  Lcg rng(seed);
  std::vector<Mutant> mutants;
  for (int k = 0; k < count; ++k) {
    Mutant m{design, ""};
    const std::size_t mutations = 1 + rng.below(3);
    for (std::size_t j = 0; j < mutations; ++j) m.text = mutate_design(m.text, rng, m.what);
    mutants.push_back(std::move(m));
  }
  return mutants;
}

std::vector<Mutant> mesh_mutants(const std::string& stl, int count, std::uint64_t seed)
{
  Lcg rng(seed);
  std::vector<Mutant> mutants;
  for (int k = 0; k < count; ++k) {
    Mutant m;
    if (binary_stl(stl)) {
      m.text = mutate_binary_stl(stl, rng, m.what);
    } else {
      m.text = mutate_design(stl, rng, m.what); // ASCII: numbers, lines and cuts as in a text
    }
    mutants.push_back(std::move(m));
  }
  return mutants;
}

} // namespace fibermold::test
