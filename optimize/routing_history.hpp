#pragma once
// The optimization's history (optimize/history.csv): one row per accepted step, with each term of
// the objective, each target's distance term and the step's figures.

#include <string>
#include <vector>

#include "optimize/minimizer.hpp"
#include "optimize/routing_problem.hpp"

namespace fibermold {

class RoutingHistory {
public:
  /// `targets`: the targets' names, one distance column each.
  explicit RoutingHistory(const std::vector<std::string>& targets);

  /// A row: iteration `iteration` of fiber stage `stage` (0-based; -1 for the routes-only run) of run
  /// `start` of [optimize] starts (0: from the first guess), `seconds` since the optimization began.
  void add(int iteration, int stage, const MinimizerIteration& it, const RoutingTerms& terms, double seconds,
           int start);

  /// The CSV text so far, with its header.
  const std::string& text() const { return text_; }

private:
  std::string text_;
};

} // namespace fibermold
