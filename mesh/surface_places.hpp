#pragma once
// Where the body's mesh meets the input surface: each surface node's place on it (a face of the
// input and barycentric weights there) and, for each input vertex, the node at it or nearest it.
// What a user gives on the input surface (a deformed copy of it, its vertex indices) reaches the
// mesh through these, whether the mesh kept the input's triangles, split them or remeshed them.

#include <vector>

#include <Eigen/Core>

#include "mesh/surface_mesh.hpp"
#include "mesh/tet_mesh.hpp"

namespace fibermold {

/// Fills mesh.surface_faces, mesh.place_face, mesh.place_weights and mesh.surface_to_node against
/// `input`, and mesh.surface_vertices with its vertices when they are not all nodes (remeshed). A node that is an input
/// vertex gets that vertex's exact place; any other surface node the nearest point of the input surface; an input
/// vertex that is no node, the nearest surface node.
void attach_to_surface(TetMesh& mesh, const SurfaceMesh& input);

/// A deformed copy of the input surface (its vertices, moved) carried to the mesh: the surface
/// nodes and where their places went. Empty places (a mesh not made from a surface): the nodes of
/// surface_to_node.
std::vector<std::pair<int, Eigen::Vector3d>> carried_surface(const TetMesh& mesh,
                                                             const Eigen::MatrixX3d& deformed_vertices);

/// The nodes a set of input vertices selects: the node at (or nearest) each, and every surface
/// node whose place lies on a face all of whose corners are selected. Sorted, without repeats.
std::vector<int> nodes_of_vertices(const TetMesh& mesh, const std::vector<int>& vertices);

} // namespace fibermold
