#include "optimize/routing_optimizer.hpp"

#include <algorithm>
#include <stdexcept>

#include <fmt/format.h>

#include "optimize/hybrid_minimizer.hpp"

namespace fibermold {

namespace {

using Mask = Eigen::Matrix<bool, Eigen::Dynamic, Eigen::Dynamic>;

/// One run (the method's) over the problem's current free variables, starting from its base.
MinimizerResult run(RoutingProblem& problem, int stage, const MinimizerOptions& options,
                    const RoutingCallback& on_iteration, Progress& progress)
{
  const IterationCallback cb = [&](const MinimizerIteration& it, const Eigen::VectorXd&) {
    if (on_iteration) on_iteration(stage, it, problem.terms_at(it.value));
  };
  const Objective f = [&](const Eigen::VectorXd& z, Eigen::VectorXd& g) { return problem.evaluate(z, &g); };
  const ModelObjective model = [&](const Eigen::VectorXd& z, Eigen::VectorXd& g, Eigen::MatrixXd& B) {
    return problem.evaluate(z, &g, nullptr, &B);
  };
  const ExactPart exact{[&](const Eigen::VectorXd& z) { return problem.regularizer_value(z); },
                        [&](const Eigen::VectorXd& z, Eigen::VectorXd& g, Eigen::MatrixXd& H) {
                          problem.regularizer_derivatives(z, g, H);
                        }};
  const Eigen::VectorXd z0 = problem.variables(problem.base());
  switch (options.method) {
  case Method::levenberg_marquardt:
    return minimize_levenberg_marquardt(model, z0, options, cb, progress, exact);
  case Method::hybrid:
    return minimize_hybrid(f, model, z0, options, cb, progress, exact);
  case Method::bfgs:
    break;
  }
  return minimize_bfgs(f, z0, options, cb, progress);
}

/// `prefix` names the run in the message (a sequential stage's fiber).
void absorb(RoutingResult& out, RoutingProblem& problem, const MinimizerResult& r, const std::string& prefix = {})
{
  out.routing = problem.routing(r.x);
  out.value = r.value;
  out.iterations += r.iterations;
  out.evaluations += r.evaluations;
  // The ending reported is the first that was not convergence, else the last run's.
  if (out.converged || r.interrupted) {
    out.termination = r.termination;
    out.message = prefix + r.message;
  }
  out.converged = out.converged && r.converged();
  out.interrupted = r.interrupted;
}

} // namespace

void free_as_optimized(RoutingProblem& problem, Strategy strategy, ActuatorMask actuators)
{
  const int T = problem.num_targets(), F = problem.num_fibers();
  if (strategy == Strategy::sequential) {
    actuators = Mask::Constant(T, F, false);
    for (int k = 0; k < std::min(T, F); ++k) actuators(k, k) = true;
  } else if (actuators.size() == 0) {
    actuators = Mask::Constant(T, F, true);
  }
  problem.set_free(std::vector<bool>(F, true), actuators, std::vector<bool>(T, true));
}

RoutingResult optimize_routing(RoutingProblem& problem, Strategy strategy, const MinimizerOptions& options,
                               const RoutingCallback& on_iteration, Progress& progress, ActuatorMask actuators)
{
  const int T = problem.num_targets(), F = problem.num_fibers();
  RoutingResult out;
  out.routing = problem.base();
  if (strategy == Strategy::simultaneous) {
    free_as_optimized(problem, strategy, std::move(actuators));
    absorb(out, problem, run(problem, 0, options, on_iteration, progress));
    return out;
  }
  if (F != T)
    throw std::invalid_argument(
        fmt::format("the sequential strategy drives one fiber per target: {} fiber(s), {} target(s)", F, T));
  for (int k = 0; k < F && !out.interrupted; ++k) {
    std::vector<bool> route(F, false), target(T, false);
    Mask pressure = Mask::Constant(T, F, false);
    for (int j = 0; j <= k; ++j) route[j] = target[j] = pressure(j, j) = true;
    problem.set_base(out.routing);
    problem.set_free(route, pressure, target);
    absorb(out, problem, run(problem, k, options, on_iteration, progress), fmt::format("fiber {}: ", k + 1));
  }
  problem.set_base(out.routing);
  return out;
}

RoutingResult optimize_pressures(RoutingProblem& problem, const MinimizerOptions& options,
                                 const RoutingCallback& on_iteration, Progress& progress, const ActuatorMask& actuators)
{
  RoutingResult out;
  out.routing = problem.base();
  problem.set_free(std::vector<bool>(problem.num_fibers(), false), actuators,
                   std::vector<bool>(problem.num_targets(), true));
  absorb(out, problem, run(problem, 0, options, on_iteration, progress));
  return out;
}

} // namespace fibermold
