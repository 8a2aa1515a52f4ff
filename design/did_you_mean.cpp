#include "design/did_you_mean.hpp"

#include <algorithm>

namespace fibermold {

std::size_t edit_distance(std::string_view a, std::string_view b)
{
  // Optimal string alignment distance: Levenshtein plus adjacent transpositions ("voxle" → "voxel").
  const std::size_t n = a.size(), m = b.size();
  std::vector<std::size_t> d((n + 1) * (m + 1));
  const auto at = [&](std::size_t i, std::size_t j) -> std::size_t& { return d[i * (m + 1) + j]; };
  for (std::size_t i = 0; i <= n; ++i) at(i, 0) = i;
  for (std::size_t j = 0; j <= m; ++j) at(0, j) = j;
  for (std::size_t i = 1; i <= n; ++i) {
    for (std::size_t j = 1; j <= m; ++j) {
      at(i, j) = std::min({at(i - 1, j) + 1, at(i, j - 1) + 1, at(i - 1, j - 1) + (a[i - 1] == b[j - 1] ? 0 : 1)});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
        at(i, j) = std::min(at(i, j), at(i - 2, j - 2) + 1);
    }
  }
  return at(n, m);
}

std::optional<std::string> closest_match(std::string_view word, const std::vector<std::string>& candidates)
{
  std::optional<std::string> best;
  if (word.size() > 100) return best; // no key or value is that long, and the table would take n·m words
  std::size_t best_distance = 0;
  for (const std::string& candidate : candidates) {
    const std::size_t d = edit_distance(word, candidate);
    const std::size_t longer = std::max(word.size(), candidate.size());
    // A prefix of one letter says nothing: "millimetres" is not "m" (metres) misspelled.
    const bool prefix =
        std::min(word.size(), candidate.size()) >= 2 && (candidate.starts_with(word) || word.starts_with(candidate));
    if (3 * d > longer && !prefix) continue;
    if (!best || d < best_distance) {
      best = candidate;
      best_distance = d;
    }
  }
  return best;
}

} // namespace fibermold
