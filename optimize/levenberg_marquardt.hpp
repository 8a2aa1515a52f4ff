#pragma once
// Levenberg-Marquardt minimization of an objective that gives, with its gradient g, a model Hessian
// B (for the routing problem: the Gauss-Newton Hessian of the tracking distance, from the forward
// sensitivities of the equilibria, plus the regularizers' Hessian). What B leaves out (the
// residuals' and equilibria's second derivatives: large where the target is not reachable) is
// learnt by a secant term S with (B + S)s = y along the last step, updated and sized as NL2SOL does
// (Dennis, Gay & Welsch 1981), and the model is M = B + S (its eigenvalues' magnitudes where the sum
// is indefinite): a structured quasi-Newton method (Dennis, Martínez & Tapia, JOTA 61(2), 1989).
// Where the objective's cheap part gives its derivatives (ExactPart below), S learns only what B
// leaves out of the rest: with them, an exact B keeps S = 0. Each step solves
//   (M + μ diag M) δ = −g,
// shortened to max_step in its largest variable, and is taken when f falls; μ follows the gain
// ratio ρ = (f(x) − f(x + δ)) / (−gᵀδ − ½ δᵀMδ) as in Nielsen's rule (Madsen, Nielsen & Tingleff,
// Methods for Non-Linear Least Squares Problems, 2004, eq. 2.21 and Algorithm 3.16): ×max(1/3,
// 1 − (2ρ − 1)³) after a step, ×ν (ν doubling) after a rejected one.
//
// Convergence is first-order and stated in the models' own metric (the Newton decrement of Boyd &
// Vandenberghe, Convex Optimization, §9.5.1): the whole decrease each of M and B predicts from x,
// ½ gᵀM⁻¹g and ½ gᵀB⁻¹g, is at most decrease_tolerance × f. Barriers raise B where they act, so a minimum held
// by a barrier converges too. It stalls where f fell by at most relative_tolerance × f over
// `window` iterations while the model predicted more than that after each of them (a wall the
// model does not know, minimizer.hpp's model_stall_message); where it predicted less, the run goes
// on to converge. The objective may return +∞ (a
// failed simulation, a barrier crossed): the step is then rejected. Steps are only taken
// downhill, so x is always the best point.
//
// A barrier's wall is what a quadratic model cannot hold: it rises to +∞ within a step that the
// model, built where the barrier was flat, takes whole. Where the objective has a part r that is
// cheap to evaluate (for the routing problem: the curvature term and the barriers, no simulation),
// the step is chosen along the ray x + αδ, α ∈ (0, 1], on the model with that part exact
// (ray_model.hpp): the quadratic model less r's second-order expansion along δ as the model holds
// it (ExactPart::derivatives; else r's own, by central differences), plus r. So a
// step stops short of a wall, or of where a barrier climbs faster than the model knew, before any
// simulation is run there (as IPC's line search is filtered by the largest step that stays
// feasible: Li et al., Incremental Potential Contact, 2020, §4.3), and the gain ratio compares f
// with what that model predicts.

#include "optimize/minimizer.hpp"

namespace fibermold {

/// f(x, g, B) returns the value and writes the gradient into g and the model Hessian into B
/// (symmetric; it need not be positive definite).
using ModelObjective =
    std::function<double(const Eigen::VectorXd& x, Eigen::VectorXd& gradient, Eigen::MatrixXd& model)>;

/// The part r of the objective that is cheap to evaluate; empty: none.
struct ExactPart {
  /// r(x), +∞ past a wall.
  std::function<double(const Eigen::VectorXd& x)> value;
  /// Where given: r's gradient at x and the Hessian of r that the model B holds. The secant term
  /// then learns only what B leaves out of the rest (y less r's gradient change, B less r's Hessian),
  /// not r's own change of curvature along a step, which B, evaluated at each point, already has.
  std::function<void(const Eigen::VectorXd& x, Eigen::VectorXd& gradient, Eigen::MatrixXd& hessian)> derivatives;

  explicit operator bool() const { return static_cast<bool>(value); }
};

/// Throws std::invalid_argument when f is not finite at x0.
MinimizerResult minimize_levenberg_marquardt(const ModelObjective& f, Eigen::VectorXd x0,
                                             const MinimizerOptions& options, const IterationCallback& on_iteration,
                                             Progress& progress, const ExactPart& exact = {});

} // namespace fibermold
