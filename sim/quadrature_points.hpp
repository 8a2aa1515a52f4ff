#pragma once
// The body's quadrature points with their shape functions, precomputed once: they do not depend
// on the deformed state (paper, end of section IV-A). Stored in Morton order of their positions,
// not tet by tet, so that the points a node's column of the Hessian reads lie close in memory.

#include <vector>

#include <Eigen/Core>

#include "mesh/tet_mesh.hpp"
#include "sim/shape_functions.hpp"

namespace fibermold {

struct QuadraturePoints {
  std::vector<Eigen::Vector3d> X; ///< rest position, m
  std::vector<double> volume;     ///< quadrature weight × tet volume, m³
  std::vector<int> offset;        ///< point q's shape functions are entries offset[q] .. offset[q+1]
  std::vector<int> node;          ///< ascending within each point
  std::vector<double> N;
  std::vector<Eigen::Vector3d> dN;

  Eigen::Index size() const { return static_cast<Eigen::Index>(X.size()); }
};

/// `points_per_tet` ∈ {1, 4, 8}; evaluated in parallel.
QuadraturePoints build_quadrature_points(const TetMesh& mesh, const Basis& basis, int points_per_tet);

/// For each node, the (quadrature point, entry) pairs that touch it: the transpose of the above,
/// so that the stiffness is assembled per node column without write conflicts.
struct NodeIncidence {
  std::vector<int> offset;                ///< size n + 1
  std::vector<std::pair<int, int>> entry; ///< (q, index into node/N/dN)
};
NodeIncidence node_incidence(const QuadraturePoints& qp, Eigen::Index num_nodes);

} // namespace fibermold
