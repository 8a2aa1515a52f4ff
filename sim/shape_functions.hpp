#pragma once
// Shape functions at a point, behind one interface for MLS and FEM bases: the deformed position
// is x(X) = Σ_i x_i N_i(X) (paper eq. 5), its gradient F = Σ_i x_i ∇N_iᵀ (eq. 8).

#include <string>
#include <vector>

#include <Eigen/Core>

namespace fibermold {

/// The shape functions that are non-zero at one point, and their derivatives.
struct ShapeEval {
  std::vector<int> nodes;           ///< the nodes i with N_i(X) ≠ 0
  Eigen::VectorXd N;                ///< N_i(X)
  Eigen::MatrixX3d dN;              ///< row i: ∇N_i(X)ᵀ
  std::vector<Eigen::Matrix3d> ddN; ///< ∇∇N_i(X); filled when second derivatives are asked for

  Eigen::Index size() const { return static_cast<Eigen::Index>(nodes.size()); }
  /// x(X) = Σ_i x_i N_i  for positions `x` stacked as 3n.
  Eigen::Vector3d position(const Eigen::VectorXd& x) const;
  /// F = Σ_i x_i ∇N_iᵀ
  Eigen::Matrix3d deformation_gradient(const Eigen::VectorXd& x) const;
};

class Basis {
public:
  virtual ~Basis() = default;
  virtual std::string name() const = 0;
  /// Shape functions at X with derivatives up to `order` (0, 1 or 2). `tet` names the element the
  /// point belongs to when known (quadrature points); FEM bases need it or locate the point.
  virtual ShapeEval at(const Eigen::Vector3d& X, int order, Eigen::Index tet = -1) const = 0;
};

} // namespace fibermold
