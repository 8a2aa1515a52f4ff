#pragma once
// Compressible Neo-Hookean elasticity integrated over the body (paper eq. 1):
//   E = Σ_q V_q Ψ(F_q),  Ψ(F) = μ/2 (tr(FᵀF) − 3) − μ ln J + λ/2 ln² J.

#include "sim/energy.hpp"
#include "sim/quadrature_points.hpp"

namespace fibermold {

struct LameParameters {
  double mu, lambda;
  static LameParameters from_young_poisson(double E, double nu)
  {
    return {E / (2 * (1 + nu)), E * nu / ((1 + nu) * (1 - 2 * nu))};
  }
};

/// Ψ, P = ∂Ψ/∂F and ∂P/∂F (9 × 9, F flattened row-major) of the Neo-Hookean density.
double neo_hookean_density(const Eigen::Matrix3d& F, const LameParameters& lame);
Eigen::Matrix3d neo_hookean_stress(const Eigen::Matrix3d& F, const LameParameters& lame);
Eigen::Matrix<double, 9, 9> neo_hookean_stress_derivative(const Eigen::Matrix3d& F, const LameParameters& lame);
/// ∂P/∂F projected onto the positive semi-definite matrices (negative eigenvalues set to zero), from
/// its closed-form eigensystem; J > 0.
Eigen::Matrix<double, 9, 9> neo_hookean_stress_derivative_psd(const Eigen::Matrix3d& F, const LameParameters& lame);

class NeoHookean final : public Energy {
public:
  NeoHookean(const QuadraturePoints& qp, Eigen::Index num_nodes, LameParameters lame);

  std::string name() const override { return "neo-hookean"; }
  double value(const Eigen::VectorXd& x) const override;
  void add_gradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const override;
  void add_hessian(const Eigen::VectorXd& x, SparseHessian& H, bool project) const override;
  void stencils(std::vector<std::vector<int>>& out) const override;
  bool is_step_valid(const Eigen::VectorXd& x) const override;
  double value_and_gradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const override;
  void add_hessian_product(const Eigen::VectorXd& x, const Eigen::VectorXd& v, Eigen::VectorXd& out) const override;
  std::unique_ptr<HessianProduct> hessian_at(const Eigen::VectorXd& x) const override;

  /// F at quadrature point q.
  Eigen::Matrix3d deformation_gradient(const Eigen::VectorXd& x, Eigen::Index q) const;

private:
  /// Points per chunk of the deterministic reductions (value, gradient).
  Eigen::Index chunk_size() const;

  const QuadraturePoints& qp_;
  NodeIncidence incidence_;
  LameParameters lame_;
};

} // namespace fibermold
