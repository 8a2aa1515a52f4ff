#pragma once
// Standard Lagrange shape functions on the tet mesh: linear (4-node, fem-p1) and quadratic
// (10-node, fem-p2), for comparison with MLS and for validating it on the same code path.

#include <memory>

#include "mesh/tet_mesh.hpp"
#include "sim/shape_functions.hpp"

namespace fibermold {

class FemBasis final : public Basis {
public:
  /// Linear or quadratic by the mesh's nodes per tet.
  explicit FemBasis(const TetMesh& mesh);
  ~FemBasis() override;

  std::string name() const override { return quadratic_ ? "fem-p2" : "fem-p1"; }
  /// In `tet` when given; otherwise in the tet that contains X (the nearest one for a point just
  /// outside the mesh).
  ShapeEval at(const Eigen::Vector3d& X, int order, Eigen::Index tet = -1) const override;

  /// The tet containing X, or the one X is least outside of.
  Eigen::Index locate(const Eigen::Vector3d& X) const;
  /// Barycentric coordinates of X in tet t and their (constant) gradients (rows).
  Eigen::Vector4d barycentric(Eigen::Index t, const Eigen::Vector3d& X,
                              Eigen::Matrix<double, 4, 3>* gradients = nullptr) const;

private:
  struct Locator;
  const TetMesh& mesh_;
  bool quadratic_;
  std::unique_ptr<Locator> locator_;
};

} // namespace fibermold
