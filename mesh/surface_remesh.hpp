#pragma once
// The body's surface remeshed to the mesh's edge length (isotropic remeshing, CGAL), its sharp edges
// kept on their polylines: a dense scan coarsened, so that [mesh] edge_length decides the simulation
// mesh. And how far the result is from the input, both ways: the remeshed vertices from the input
// surface, and the input's vertices from the remeshed surface (a feature lost shows there).

#include <Eigen/Core>

#include "mesh/surface_mesh.hpp"

namespace fibermold {

/// Edges sharper than this (the angle between the faces' normals) stay edges of the remeshed surface.
inline constexpr double kSharpEdgeDeg = 60;

struct RemeshReport {
  Eigen::Index faces_before = 0, faces_after = 0;
  Eigen::Index sharp_edges = 0; ///< input edges kept as constraints
};

/// `surface` must be closed and valid (check_surface). Throws std::runtime_error when the remeshed
/// surface is not.
SurfaceMesh remesh_surface(const SurfaceMesh& surface, double edge_length, RemeshReport& report);

struct SurfaceDeviation {
  double remeshed_from_input = 0; ///< m: largest distance of a remeshed vertex from the input surface
  double input_from_remeshed = 0; ///< m: largest distance of an input vertex from the remeshed surface
  Eigen::Vector3d worst_at = Eigen::Vector3d::Zero(); ///< the input vertex farthest from the remeshed surface
  Eigen::Index input_vertices_beyond = 0;             ///< input vertices farther than `beyond` from it
};
SurfaceDeviation surface_deviation(const SurfaceMesh& input, const SurfaceMesh& remeshed, double beyond);

} // namespace fibermold
