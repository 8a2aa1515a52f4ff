#include "optimize/first_guess_comparison.hpp"

#include <algorithm>
#include <vector>

#include <fmt/format.h>

namespace fibermold {

namespace {
struct TermChange {
  const char* name;
  const char* setting; ///< the design-file key that weighs it
  double before, after;
};

/// The barrier and regularizer terms that fell from the first guess to the optimized routing, the
/// largest fall first: what the optimizer spent the targets' match on.
std::string what_fell(const RoutingTerms& first_guess, const RoutingTerms& optimized)
{
  std::vector<TermChange> changes{
      {"the skin barrier", "[optimize] weight_skin_barrier", first_guess.skin, optimized.skin},
      {"the bend barrier", "[optimize] weight_bend_barrier", first_guess.bend, optimized.bend},
      {"the curvature regularizer", "[optimize] weight_curvature", first_guess.curvature, optimized.curvature},
      {"the pressure barrier", "[optimize] weight_pressure_barrier", first_guess.pressure, optimized.pressure},
      {"the fibers' clearance barrier", "[collide] clearance", first_guess.clearance, optimized.clearance}};
  std::erase_if(changes, [](const TermChange& c) { return !(c.after < c.before); });
  std::stable_sort(changes.begin(), changes.end(),
                   [](const TermChange& a, const TermChange& b) { return a.before - a.after > b.before - b.after; });
  if (changes.empty()) return "the barriers and regularizers";
  std::string out;
  for (std::size_t i = 0; i < changes.size() && i < 2; ++i)
    out += fmt::format("{}{} {:.4g} -> {:.4g} ({})", i ? ", " : "", changes[i].name, changes[i].before,
                       changes[i].after, changes[i].setting);
  return out;
}
} // namespace

FirstGuessComparison compare_with_first_guess(const RoutingTerms& first_guess, const RoutingTerms& optimized)
{
  if (first_guess.total < optimized.total)
    return {true, fmt::format("the optimizer ended at an objective of {:.4g}, above the first guess's at its best "
                              "pressures ({:.4g}): the first guess is kept; start the routes elsewhere or raise "
                              "[optimize] max_iterations",
                              optimized.total, first_guess.total)};
  if (first_guess.distance < (1 - kWorseMatch) * optimized.distance)
    return {true, fmt::format("the optimized routes match the targets less well than the first guess at its best "
                              "pressures (distance {:.4g} against {:.4g}); they lowered the objective ({:.4g} against "
                              "{:.4g}) through {}, not the targets: the first guess is kept. Lower the setting named "
                              "to let the routes go where the targets want them",
                              optimized.distance, first_guess.distance, optimized.total, first_guess.total,
                              what_fell(first_guess, optimized))};
  return {};
}

} // namespace fibermold
