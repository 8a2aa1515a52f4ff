#include "optimize/full_turn_search.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/progress.hpp"

namespace fibermold {

std::optional<FullTurn> full_turn_search(double angle, double s0, double a0, double s1, double a1, double most,
                                         const std::function<double(double)>& turn_at, const FullTurnOptions& options)
{
  std::optional<FullTurn> best; // the solved scale nearest the angle
  const auto within = [&](double a) { return std::abs(a - angle) <= options.tolerance * std::abs(angle); };
  for (int k = 0; k < options.solves; ++k) {
    if (!((a1 - a0) / angle > 0)) break; // the turn does not grow toward the angle there
    const double s = std::min(most, s1 + (angle - a1) * (s1 - s0) / (a1 - a0)); // the secant step
    if (!(s > 0) || (best && s == best->scale)) break;
    double a = 0;
    try {
      a = turn_at(s);
    } catch (const Interrupted&) {
      throw; // a runtime_error too: Ctrl-C stops the search, it does not end it quietly
    } catch (const std::runtime_error&) {
      break; // no equilibrium there: the nearest so far stands
    }
    if (!best || std::abs(a - angle) < std::abs(best->turn - angle)) best = FullTurn{s, a, s == most, within(a)};
    if (within(a) || (s == most && a / angle < 1)) break;
    s0 = s1, a0 = a1, s1 = s, a1 = a;
  }
  return best;
}

} // namespace fibermold
