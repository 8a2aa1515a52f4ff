#pragma once
// A whole optimization as the optimize stage runs it: with `route_only_iterations`, first the routes
// alone at their starting pressures (reported as stage −1), then routes and pressures; and with
// `starts` = N, that from the first guess and from N − 1 perturbations of it (perturbed_start.hpp),
// keeping the run that ends lowest. At zero pressure a route has no effect, so an optimizer that
// turns a muscle down before its route does the job can stop there (the twisting bar: a straight
// muscle bends the bar, so its pressure falls to zero before a helix forms).

#include <string>
#include <vector>

#include "optimize/routing_optimizer.hpp"

namespace fibermold {

struct SeveralStartsOptions {
  Strategy strategy = Strategy::simultaneous;
  MinimizerOptions minimizer;
  ActuatorMask actuators; ///< empty: every fiber for every target
  int route_only_iterations = 0;
  int starts = 1;
  double spread = 0; ///< m: how far a perturbed start moves each control point (RMS per coordinate)
};

/// How one start's run ended.
struct StartRun {
  int start = 0;        ///< 0: from the first guess
  std::string left_out; ///< why the start was left out (Newton found no equilibrium there); empty: it ran
  RoutingResult result; ///< its end (without its routing when left out)
};

/// The run that ends lowest over the starts (interrupted: the best so far, marked interrupted);
/// each start's ending in `runs`. `current` is the start being run, for the callback. A perturbed
/// start where the objective is not finite (no equilibrium) is left out; the first guess's throws.
/// Leaves the problem's base at `start`.
RoutingResult optimize_from_starts(RoutingProblem& problem, const Routing& start, const SeveralStartsOptions& options,
                                   const RoutingCallback& on_iteration, Progress& progress, int& current,
                                   std::vector<StartRun>& runs);

} // namespace fibermold
