#pragma once
// The hybrid minimizer: BFGS (bfgs.hpp) while it makes progress, then Levenberg-Marquardt
// (levenberg_marquardt.hpp) from where it slowed down. BFGS is cheap per step and robust far from
// the optimum, where the Gauss-Newton model of a large design change is poor; near the optimum its
// quasi-Newton matrix learns an ill-conditioned valley slowly, and it crawls and stalls short of a
// stationary point, where a model built from the sensitivities, with its secant term, converges.
// BFGS hands over where f fell by less than switch_tolerance (1 %) of itself over `window`
// iterations: on the examples that converged on three of seven, a later switch (at
// relative_tolerance, 0.1 %) on two, in the same time (docs/optimize.md, "Choosing the optimizer").

#include "optimize/levenberg_marquardt.hpp"

namespace fibermold {

/// BFGS on f; where it slowed down (switch_tolerance) or its line search failed with iterations left,
/// Levenberg-Marquardt on `model` (with `exact`) from BFGS's best point for the rest of max_iterations. Iterations are
/// numbered on across the switch; the result's ending is the last run's, its message names both. Throws
/// std::invalid_argument when f is not finite at x0.
MinimizerResult minimize_hybrid(const Objective& f, const ModelObjective& model, Eigen::VectorXd x0,
                                const MinimizerOptions& options, const IterationCallback& on_iteration,
                                Progress& progress, const ExactPart& exact = {});

} // namespace fibermold
