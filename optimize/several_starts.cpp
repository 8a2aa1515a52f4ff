#include "optimize/several_starts.hpp"

#include <stdexcept>
#include <utility>

#include "optimize/perturbed_start.hpp"

namespace fibermold {

namespace {

/// One start's run: the routes alone for route_only_iterations, then everything.
RoutingResult optimize_routes_first(RoutingProblem& problem, const SeveralStartsOptions& o,
                                    const RoutingCallback& on_iteration, Progress& progress)
{
  if (o.route_only_iterations == 0)
    return optimize_routing(problem, o.strategy, o.minimizer, on_iteration, progress, o.actuators);
  MinimizerOptions first = o.minimizer;
  first.max_iterations = o.route_only_iterations;
  const ActuatorMask none = ActuatorMask::Constant(problem.num_targets(), problem.num_fibers(), false);
  const RoutingCallback routes_only = [&](int, const MinimizerIteration& it, const RoutingTerms& terms) {
    on_iteration(-1, it, terms);
  };
  const RoutingResult routes = optimize_routing(problem, Strategy::simultaneous, first, routes_only, progress, none);
  if (routes.interrupted) return routes;
  problem.set_base(routes.routing);
  RoutingResult both = optimize_routing(problem, o.strategy, o.minimizer, on_iteration, progress, o.actuators);
  both.iterations += routes.iterations;
  both.evaluations += routes.evaluations;
  return both;
}

} // namespace

RoutingResult optimize_from_starts(RoutingProblem& problem, const Routing& start, const SeveralStartsOptions& options,
                                   const RoutingCallback& on_iteration, Progress& progress, int& current,
                                   std::vector<StartRun>& runs)
{
  RoutingResult best;
  runs.clear();
  for (int k = 0; k < options.starts; ++k) {
    current = k;
    const Routing from = k == 0 ? start : perturbed_start(problem, start, k, options.spread);
    problem.set_base(from);
    RoutingResult r;
    try {
      r = optimize_routes_first(problem, options, on_iteration, progress);
    } catch (const std::invalid_argument& e) { // a perturbed start whose equilibrium Newton does not find
      if (k == 0) throw;
      runs.push_back({k, e.what(), {}});
      continue;
    }
    runs.push_back({k, "", r});
    runs.back().result.routing = {};
    const bool interrupted = r.interrupted;
    if (k == 0 || r.value < best.value) best = std::move(r);
    if (interrupted) {
      best.interrupted = true; // the best design so far is kept
      break;
    }
  }
  if (options.starts > 1) problem.set_base(start); // a single run leaves it as it always did
  return best;
}

} // namespace fibermold
