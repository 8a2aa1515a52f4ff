#pragma once
// Quadrature rules on tetrahedra, in barycentric coordinates with weights that sum to 1 (multiply
// by the tet's volume).

#include <vector>

#include <Eigen/Core>

namespace fibermold {

struct TetQuadrature {
  std::vector<Eigen::Vector4d> barycentric;
  std::vector<double> weights;
  int degree = 0; ///< polynomials up to this degree are integrated exactly
};

/// 1 point (degree 1), 4 points (degree 2), or 8 points: the Stroud conical product of 2-point
/// Gauss–Jacobi rules (degree 3), the paper's 8-point Gauss rule (section IV-B).
/// Throws std::invalid_argument for any other count.
const TetQuadrature& tet_quadrature(int points);

} // namespace fibermold
