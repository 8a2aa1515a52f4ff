#pragma once
// Exact booleans and plane cuts of closed triangle meshes (CGAL corefinement, Polygon Mesh
// Processing clip). Inputs must be closed, outward-oriented and free of self-intersections; every
// function throws std::runtime_error naming the operation when CGAL cannot produce a valid solid.

#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "mesh/surface_mesh.hpp"

namespace fibermold {

SurfaceMesh mesh_difference(const SurfaceMesh& a, const SurfaceMesh& b);
SurfaceMesh mesh_union(const SurfaceMesh& a, const SurfaceMesh& b);
SurfaceMesh mesh_intersection(const SurfaceMesh& a, const SurfaceMesh& b);
/// a ∪ b for solids that touch. Where they share only an edge the exact union is not manifold and
/// corefinement fails; b is then moved by `nudge` (a few µm, into a) so that they overlap in a thin
/// slab instead, and the union is taken again.
SurfaceMesh mesh_union_touching(const SurfaceMesh& a, SurfaceMesh b, const Eigen::Vector3d& nudge);

/// The parts of a closed mesh below and above the plane through `point` with `normal` (below: on the
/// side −normal), each closed by the cut.
std::pair<SurfaceMesh, SurfaceMesh> split_by_plane(const SurfaceMesh& m, const Eigen::Vector3d& point,
                                                   const Eigen::Vector3d& normal);

/// m without its zero-area faces (CGAL's remove_degenerate_faces, which keeps the surface closed).
/// Rotating a boolean's result can round a sliver's three corners onto one line.
SurfaceMesh without_degenerate_faces(const SurfaceMesh& m);

/// Connected surface components: a solid with an internal void has two.
int count_shells(const SurfaceMesh& m);
/// The connected surface components, each a mesh of its own, in the order of their first face.
std::vector<SurfaceMesh> split_shells(const SurfaceMesh& m);

} // namespace fibermold
