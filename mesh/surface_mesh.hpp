#pragma once
// A triangle surface: the body's skin as the user gave it, in metres.

#include <filesystem>
#include <vector>

#include <Eigen/Core>

namespace fibermold {

struct SurfaceMesh {
  Eigen::MatrixX3d vertices;    ///< m
  Eigen::MatrixX3i faces;       ///< counter-clockwise seen from outside
  std::filesystem::path source; ///< the file it came from, for messages

  Eigen::Index num_vertices() const { return vertices.rows(); }
  Eigen::Index num_faces() const { return faces.rows(); }
};

/// The same triangles in a canonical order: vertices sorted by position (x, then y, then z; ties
/// keep their order), each face starting at its least vertex (its turn kept), faces sorted. Two
/// lists of the same triangles give the same mesh byte for byte, whatever order a library made
/// them in (CGAL's booleans and OpenVDB's mesher do not keep one from run to run with threads).
SurfaceMesh canonical_order(const SurfaceMesh& surface);

/// Volume enclosed by a closed, consistently oriented surface (divergence theorem); negative when
/// the faces point inward.
double signed_volume(const SurfaceMesh& surface);

/// The longest and the mean edge of the surface's triangles (each edge counted once per face).
double longest_edge(const SurfaceMesh& surface);
double mean_edge_length(const SurfaceMesh& surface);

/// The surface's area.
double surface_area(const SurfaceMesh& surface);

/// The connected component ("shell") of each face, numbered 0, 1, ... in the order of their first
/// face: faces sharing a vertex are in the same shell.
std::vector<int> face_shells(const SurfaceMesh& surface);

} // namespace fibermold
