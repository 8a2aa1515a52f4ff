#pragma once
// Size and quality figures of a tetrahedral mesh, for the mesh report.

#include <cmath>

#include "mesh/tet_mesh.hpp"

namespace fibermold {

struct MeshQuality {
  double volume = 0;                               ///< m³
  double mean_edge_length = 0;                     ///< m, over the unique corner edges
  double min_edge_length = 0, max_edge_length = 0; ///< m
  double min_dihedral_deg = 0, max_dihedral_deg = 0;
  double mean_radius_edge_ratio = 0; ///< circumradius / shortest edge; 0.612 for a regular tet
  double max_radius_edge_ratio = 0;
  Eigen::Index inverted_tets = 0; ///< non-positive volume
  /// The tets outside the quality bounds asked for: a radius-edge ratio above `max_ratio` or a
  /// dihedral angle below `min_dihedral_deg` (TetGen cannot meet them next to a surface it must keep).
  Eigen::Index over_ratio = 0, under_dihedral = 0;
  Eigen::Vector3d worst_at = Eigen::Vector3d::Zero(); ///< the centroid of the tet of largest ratio
};

/// The mesh's quality, and the tets outside the bounds (none asked for by default).
MeshQuality mesh_quality(const TetMesh& mesh, double max_ratio = HUGE_VAL, double min_dihedral_deg = 0);

/// The mean length of the mesh's unique corner edges (m): what [mesh] edge_length asks for.
double mean_edge_length(const TetMesh& mesh);

/// Circumradius over shortest edge of the tet with corners a, b, c, d.
double radius_edge_ratio(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                         const Eigen::Vector3d& d);

} // namespace fibermold
