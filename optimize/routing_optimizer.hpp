#pragma once
// The two strategies of section V-B for several fibers:
//  - simultaneous: every route and every (target, fiber) pressure at once, all targets (or the
//    pressures of each target's own actuators);
//  - sequential: one fiber per target, only fiber k pressurized in target k (orthogonal
//    actuators). Fibers are added one at a time: stage k moves the routes of fibers 1..k and counts
//    targets 1..k, each with its own fiber's pressure, so that a later fiber (stiff even when
//    unpressurized) cannot spoil an earlier target. Each stage starts where the last one ended.

#include <functional>
#include <string>

#include "core/names.hpp"
#include "optimize/bfgs.hpp"
#include "optimize/routing_problem.hpp"

namespace fibermold {

struct RoutingResult {
  Routing routing;
  double value = 0; ///< objective at the end (of the last stage for sequential)
  int iterations = 0, evaluations = 0;
  /// Why it stopped: the first run (of a sequential one's stages) that did not converge, else the
  /// last; `converged` only when every run met the gradient tolerance.
  Termination termination = Termination::iteration_limit;
  bool converged = true, interrupted = false;
  std::string message;
};

/// Called after each accepted step: the stage (0 for simultaneous, fiber k for sequential), the
/// step, and the terms at the new point.
using RoutingCallback = std::function<void(int stage, const MinimizerIteration&, const RoutingTerms&)>;

/// Which fibers may be pressurized for which target (targets × fibers); the others keep the
/// pressure they start with (0 for an unassigned fiber).
using ActuatorMask = Eigen::Matrix<bool, Eigen::Dynamic, Eigen::Dynamic>;

/// How the fibers are optimized (paper section VI): all at once for all targets, or fiber k for
/// target k, one after the other with the earlier ones fixed.
enum class Strategy { simultaneous, sequential };
inline constexpr std::array<Named<Strategy>, 2> kStrategyNames{
    {{Strategy::simultaneous, "simultaneous"}, {Strategy::sequential, "sequential"}}};
inline std::string_view choice_name(Strategy s) { return name_in(kStrategyNames, s); }

/// Frees what the last run of optimize_routing frees, so that evaluate scores its objective: every
/// route, every target, and the pressures `actuators` gives (simultaneous; empty: all) or fiber k's
/// for target k (sequential). Resets the problem's best evaluation (RoutingProblem::set_free).
void free_as_optimized(RoutingProblem& problem, Strategy strategy, ActuatorMask actuators = {});

/// `actuators` applies to simultaneous (empty: every fiber for every target). Throws
/// std::invalid_argument for sequential with a number of fibers different from the number of
/// targets.
RoutingResult optimize_routing(RoutingProblem& problem, Strategy strategy, const MinimizerOptions& options,
                               const RoutingCallback& on_iteration, Progress& progress, ActuatorMask actuators = {});

/// The first guess's routes at their best pressures: a pressure-only run (the routes held), over
/// the pressures `actuators` frees. Every optimization is measured against it (docs/optimize.md).
RoutingResult optimize_pressures(RoutingProblem& problem, const MinimizerOptions& options,
                                 const RoutingCallback& on_iteration, Progress& progress,
                                 const ActuatorMask& actuators);

} // namespace fibermold
