#pragma once
// The volumetric mesh of the body that later stages simulate on: nodes, tetrahedra (4 or 10
// nodes), boundary faces, and how its surface sits on the input surface (mesh/surface_places.hpp).

#include <filesystem>

#include <Eigen/Core>

#include "mesh/surface_mesh.hpp"

namespace fibermold {

struct TetMesh {
  Eigen::MatrixX3d nodes;                                  ///< m
  Eigen::Matrix<int, Eigen::Dynamic, Eigen::Dynamic> tets; ///< 4 columns (linear) or 10 (quadratic, VTK order)
  Eigen::MatrixX3i boundary_faces;                         ///< corner nodes, outward
  Eigen::VectorXi surface_to_node;                         ///< input surface vertex → the node at it (or nearest it)
  Eigen::MatrixX3i surface_faces;                          ///< the input surface's faces (its vertex indices)
  Eigen::MatrixX3d surface_vertices; ///< m, the input's vertices when they are not all nodes (remeshed); else empty
  Eigen::VectorXi place_face;        ///< node → the input face its place is on; −1 inside
  Eigen::MatrixX3d place_weights;    ///< node → barycentric weights of its place on that face

  int nodes_per_tet() const { return static_cast<int>(tets.cols()); }
  Eigen::Index num_tets() const { return tets.rows(); }

  /// Signed volume of tet t from its four corners (positive when positively oriented).
  double tet_volume(Eigen::Index t) const;
  double volume() const;
};

/// The mesh's skin (its boundary faces) over only the nodes it uses, placed at `nodes` (the mesh's
/// nodes, at rest or deformed): a closed surface to write as STL.
SurfaceMesh boundary_surface(const TetMesh& mesh, const Eigen::MatrixX3d& nodes);

/// Binary artifact for later stages (mesh/body.tetmesh): little-endian, versioned, with a checksum.
void save_tet_mesh(const TetMesh& mesh, const std::filesystem::path& path);
/// Throws std::runtime_error naming the file when it is missing, truncated or corrupt.
TetMesh load_tet_mesh(const std::filesystem::path& path);

} // namespace fibermold
