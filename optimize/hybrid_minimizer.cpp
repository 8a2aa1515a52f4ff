#include "optimize/hybrid_minimizer.hpp"

#include <fmt/format.h>

#include "optimize/bfgs.hpp"

namespace fibermold {

MinimizerResult minimize_hybrid(const Objective& f, const ModelObjective& model, Eigen::VectorXd x0,
                                const MinimizerOptions& options, const IterationCallback& on_iteration,
                                Progress& progress, const ExactPart& exact)
{
  MinimizerOptions first = options;
  first.relative_tolerance = options.switch_tolerance;
  MinimizerResult bfgs = minimize_bfgs(f, std::move(x0), first, on_iteration, progress);
  const bool switch_over = bfgs.termination == Termination::stalled || bfgs.termination == Termination::line_search;
  if (!switch_over || bfgs.iterations >= options.max_iterations) return bfgs;
  MinimizerOptions rest = options;
  rest.max_iterations = options.max_iterations - bfgs.iterations;
  const IterationCallback numbered_on = [&](const MinimizerIteration& it, const Eigen::VectorXd& x) {
    MinimizerIteration numbered = it;
    numbered.iteration += bfgs.iterations;
    numbered.evaluations += bfgs.evaluations;
    if (on_iteration) on_iteration(numbered, x);
  };
  MinimizerResult lm = minimize_levenberg_marquardt(model, bfgs.x, rest, numbered_on, progress, exact);
  if (lm.interrupted && !(lm.value < bfgs.value)) { // stopped before it found better
    lm.x = bfgs.x;
    lm.value = bfgs.value;
    lm.gradient_norm = bfgs.gradient_norm;
  }
  lm.iterations += bfgs.iterations;
  lm.evaluations += bfgs.evaluations;
  lm.message = fmt::format("BFGS {} after {} iterations (f = {:.6g}); Levenberg-Marquardt from there: {}",
                           choice_name(bfgs.termination), bfgs.iterations, bfgs.value, lm.message);
  return lm;
}

} // namespace fibermold
