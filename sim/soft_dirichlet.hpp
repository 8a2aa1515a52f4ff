#pragma once
// Soft Dirichlet conditions on fixed regions: a penalty on the distance of the deformation field,
// evaluated at each held node's rest position, from that position (MLS does not interpolate
// nodes, so x(X_i) = Σ_j N_j(X_i) x_j, not x_i, is held; paper section IV-A):
//   E = k/2 Σ_i |x(X_i) − X̂_i|²

#include "sim/energy.hpp"
#include "sim/shape_functions.hpp"

namespace fibermold {

class SoftDirichlet final : public Energy {
public:
  /// `at_nodes[k]`: shape functions at the k-th held point; `targets[k]`: where it is held (m);
  /// `stiffness` k in N/m.
  SoftDirichlet(std::vector<ShapeEval> at_nodes, std::vector<Eigen::Vector3d> targets, double stiffness);

  std::string name() const override { return "soft dirichlet"; }
  double value(const Eigen::VectorXd& x) const override;
  void add_gradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const override;
  void add_hessian(const Eigen::VectorXd& x, SparseHessian& H, bool project) const override;
  void add_hessian_product(const Eigen::VectorXd& x, const Eigen::VectorXd& v, Eigen::VectorXd& out) const override;
  void stencils(std::vector<std::vector<int>>& out) const override;

  /// Holds points first, first + 1, … at `targets` instead (the Hessian, k N_i N_j I, is unchanged).
  void move_targets(std::size_t first, const std::vector<Eigen::Vector3d>& targets);

private:
  std::vector<ShapeEval> at_;
  std::vector<Eigen::Vector3d> targets_;
  double k_;
};

} // namespace fibermold
