#pragma once
// Repairing a surface on request ([mesh] repair = true), never silently: merge vertices closer than
// a tolerance, drop degenerate and duplicate faces and unused vertices, make the orientation
// consistent, stitch borders, fill small holes, orient outward (CGAL). Remeshing is
// mesh/surface_remesh.hpp.

#include <string>
#include <vector>

#include "mesh/surface_mesh.hpp"

namespace fibermold {

struct RepairOptions {
  double merge_tolerance = 1e-6; ///< × bounding-box diagonal
};

/// A hole bounded by at most this many edges (left by a missing face or a few: an export's dropped
/// triangle) is filled with triangles on its border (CGAL's minimal-area triangulation); a larger one
/// is a missing part of the body, which only its author can restore.
inline constexpr std::size_t kLargestFilledHole = 12;

struct RepairReport {
  std::size_t merged_vertices = 0;
  std::size_t removed_faces = 0;    ///< degenerate or duplicate
  std::size_t removed_vertices = 0; ///< used by no face
  bool reoriented = false;          ///< some faces flipped to agree with their neighbours
  std::size_t stitched_edges = 0;
  std::size_t filled_holes = 0, hole_faces = 0; ///< holes of at most kLargestFilledHole edges, the faces added
  bool turned_outward = false;                  ///< the whole surface was inside out
  std::size_t faces_before = 0, faces_after = 0;

  /// What changed, one line per change; empty when nothing did.
  std::vector<std::string> changes() const;
};

SurfaceMesh repair_surface(const SurfaceMesh& surface, const RepairOptions& options, RepairReport& report);

} // namespace fibermold
