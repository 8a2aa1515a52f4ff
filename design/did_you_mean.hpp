#pragma once
// "Did you mean" hints for misspelled keys and names.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace fibermold {

/// Levenshtein distance (insertions, deletions, substitutions; case-sensitive).
std::size_t edit_distance(std::string_view a, std::string_view b);

/// The candidate closest to `word`, if it is close enough to be a plausible misspelling
/// (at most a third of the longer word's letters differ, or one of two letters or more is a prefix
/// of the other).
std::optional<std::string> closest_match(std::string_view word, const std::vector<std::string>& candidates);

} // namespace fibermold
