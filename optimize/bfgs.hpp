#pragma once
// Quasi-Newton minimization with the standard (dense) BFGS update of the inverse Hessian
// (Nocedal & Wright, Numerical Optimization, eq. 6.17, with the initial scaling of eq. 6.20) and
// LBFGSpp's backtracking line search on the Wolfe conditions. A design has tens to hundreds of
// variables, so the dense n×n matrix is cheap next to one simulation.
//
// The objective may return +∞ (a failed simulation, a barrier crossed): the line search then
// shrinks the step. The best point evaluated is always what is returned.

#include "optimize/minimizer.hpp"

namespace fibermold {

/// Throws std::invalid_argument when f is not finite at x0.
MinimizerResult minimize_bfgs(const Objective& f, Eigen::VectorXd x0, const MinimizerOptions& options,
                              const IterationCallback& on_iteration, Progress& progress);

} // namespace fibermold
