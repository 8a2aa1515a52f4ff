#pragma once
// Tetrahedralizing the body with TetGen: a constrained, quality mesh that keeps the input surface
// exactly (no Steiner points on it), so that every surface vertex is a node and the boundary faces
// are the input faces. Second-order (10-node) tetrahedra on request.

#include "core/progress.hpp"
#include "mesh/surface_mesh.hpp"
#include "mesh/tet_mesh.hpp"

namespace fibermold {

struct TetOptions {
  double edge_length = 0;          ///< m, target; sets TetGen's volume bound a³/(6√2)
  double radius_edge_ratio = 1.5;  ///< TetGen's quality bound (-q)
  double min_dihedral_deg = 10;    ///< TetGen's dihedral-angle bound (-q.../angle)
  bool quadratic = false;          ///< 10-node tetrahedra (-o2)
};

/// The surface must have passed check_surface(). Throws std::runtime_error when TetGen fails.
TetMesh tetrahedralize(const SurfaceMesh& surface, const TetOptions& options, Progress& progress);

/// Volume of a regular tetrahedron with edge `a`: a³/(6√2).
double regular_tet_volume(double a);

} // namespace fibermold
