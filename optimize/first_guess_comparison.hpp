#pragma once
// The optimized routing held against the first guess at its best pressures (the user's routes as
// drawn, pressurized as well as they can be): the optimize stage keeps the first guess where the
// optimizer ended with a higher objective, or where it matches the targets less well (a higher
// distance term) and lowered the objective only through its barriers and regularizers. Those
// keep routes legal and smooth; the first guess is both, and the targets are what the user asked.

#include <string>

#include "optimize/routing_problem.hpp"

namespace fibermold {

/// A distance this much (relative) above the first guess's is a worse match; closer is round-off.
inline constexpr double kWorseMatch = 1e-9;

struct FirstGuessComparison {
  bool keep_first_guess = false;
  std::string warning; ///< why the first guess is kept, with the figures and what to try; empty else
};

/// `first_guess` and `optimized`: the terms of each, scored as the optimization scores (the same
/// weights and counted targets); `first_guess.total` finite.
FirstGuessComparison compare_with_first_guess(const RoutingTerms& first_guess, const RoutingTerms& optimized);

} // namespace fibermold
