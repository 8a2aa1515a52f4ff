#pragma once
// The model of an objective along a step's ray x + αδ with its cheap part r exact
// (levenberg_marquardt.hpp): with g and M the gradient and model Hessian at x,
//   m(α) = f + α gᵀδ + ½α² δᵀMδ − (α r₁ + ½α² r₂) + r(x + αδ) − r(x),
// r₁, r₂ r's first and second derivatives along δ at x as M holds them (∇rᵀδ and δᵀRδ, R the
// Hessian of r in M, where the caller has them; else central differences of r). m keeps the quadratic
// model of what r is not (the tracking distance's Gauss-Newton part) and takes r's exact values,
// +∞ past its walls, so a step is chosen where the barriers really are.

#include <functional>

#include <Eigen/Core>

namespace fibermold {

struct RayStep {
  double alpha = 1;     ///< the step taken is αδ
  double predicted = 0; ///< f − m(α): the decrease the model predicts for it (≤ 0: none on the ray)
};

/// The α in (0, 1] with the least m(α), among halvings of the step refined by golden-section
/// search; where r is not finite around x (a wall within a ten-millionth of δ), the quadratic model's
/// full step.
RayStep ray_step(const std::function<double(const Eigen::VectorXd&)>& r, const Eigen::VectorXd& x,
                 const Eigen::VectorXd& g, const Eigen::MatrixXd& M, const Eigen::VectorXd& delta);
/// The same with r's expansion along δ given: r₁ = ∇rᵀδ and r₂ = δᵀRδ for the Hessian R of r in
/// the model B that M is built from, so that m takes out the part of M that r's exact values
/// replace (where M is B + S with its eigenvalues' magnitudes, as much as B holds). With r₂ from
/// central differences of r, B's projected R, positive semi-definite where r is not (a skin barrier
/// along a notch), was left in m as a curvature no term has, and it cut the steps short. Unlike
/// the overload above it has no fallback for r not finite just behind x: it searches the ray.
RayStep ray_step(const std::function<double(const Eigen::VectorXd&)>& r, const Eigen::VectorXd& x,
                 const Eigen::VectorXd& g, const Eigen::MatrixXd& M, const Eigen::VectorXd& delta, double r1,
                 double r2);

} // namespace fibermold
