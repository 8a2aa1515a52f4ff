#pragma once
// Dead loads: gravity and the user's loads, all of the form E = −fᵀx with a constant nodal force
// vector f (work done by the external forces).

#include <array>
#include <optional>

#include "mesh/tet_mesh.hpp"
#include "sim/energy.hpp"
#include "sim/quadrature_points.hpp"
#include "sim/shape_functions.hpp"

namespace fibermold {

class ExternalForces final : public Energy {
public:
  explicit ExternalForces(Eigen::VectorXd f) : f_(std::move(f)) {}
  std::string name() const override { return "external forces"; }
  double value(const Eigen::VectorXd& x) const override { return -f_.dot(x); }
  void add_gradient(const Eigen::VectorXd&, Eigen::VectorXd& g) const override { g -= f_; }
  void add_hessian(const Eigen::VectorXd&, SparseHessian&, bool) const override {}
  void add_hessian_product(const Eigen::VectorXd&, const Eigen::VectorXd&, Eigen::VectorXd&) const override {}
  void stencils(std::vector<std::vector<int>>&) const override {}
  const Eigen::VectorXd& forces() const { return f_; }

private:
  Eigen::VectorXd f_;
};

/// m_i = Σ_q V_q ρ N_i(X_q): the consistent nodal masses.
Eigen::VectorXd nodal_masses(const QuadraturePoints& qp, Eigen::Index num_nodes, double density);

/// Positive nodal volumes w_i = Σ_q V_q |N_i(X_q)| (lumped): the weights that spread a load over a
/// region, whatever the density, and never in the wrong direction (consistent masses of quadratic
/// bases are negative at some nodes).
Eigen::VectorXd nodal_volumes(const QuadraturePoints& qp, Eigen::Index num_nodes);

/// Gravity: f_i = m_i g.
Eigen::VectorXd gravity_forces(const Eigen::VectorXd& masses, const Eigen::Vector3d& g);

/// A total force spread over `nodes` (distinct) in proportion to their weights.
Eigen::VectorXd region_force(const std::vector<int>& nodes, const Eigen::VectorXd& weights, const Eigen::MatrixX3d& X,
                             const Eigen::Vector3d& force);

/// A torque about the weighted centre c of `nodes` (distinct): f_i = w_i (J⁻¹ T) × r_i with
/// r_i = X_i − c and J = Σ w_i (|r_i|² I − r_i r_iᵀ), so that Σ r_i × f_i = T and Σ f_i = 0.
/// Throws std::invalid_argument when the nodes are collinear (J singular: no torque can be applied).
Eigen::VectorXd region_torque(const std::vector<int>& nodes, const Eigen::VectorXd& weights, const Eigen::MatrixX3d& X,
                              const Eigen::Vector3d& torque);

/// A force at point P: f_i = N_i(P) F.
Eigen::VectorXd point_force(const ShapeEval& at_point, Eigen::Index num_nodes, const Eigen::Vector3d& force);

/// Nodes whose rest position lies in the box [lo, hi] (with a relative tolerance of 1e-9 of the box).
std::vector<int> nodes_in_box(const Eigen::MatrixX3d& X, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi);

} // namespace fibermold
