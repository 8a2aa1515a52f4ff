#pragma once
// `fibermold check`: what every stage would refuse of a design, found before any of them runs, by
// the stages' own rules (each stage's require_* function), as ceres' Solver::Options::IsValid
// gathers every option's rule: the surface (closed, manifold, outward), the mesh's size and the
// refined one's, the mold grids, the starting routes against the skin and the bend radius, the
// fixed regions and poses, and the surface targets.

#include <string>
#include <vector>

#include <Eigen/Core>

#include "design/design.hpp"
#include "mesh/surface_check.hpp"

namespace fibermold {

/// What `fibermold check` says about the surface and the mesh to come.
struct DesignSurfaceCheck {
  SurfaceCheck surface;
  std::vector<std::string> repairs; ///< what [mesh] repair = true changes
  double edge_length = 0;           ///< m, asked or by default
  SurfaceTriangles treatment = SurfaceTriangles::keep;
  double estimated_tets = 0;                                                  ///< expected_tets
  Eigen::Vector3d lo = Eigen::Vector3d::Zero(), hi = Eigen::Vector3d::Zero(); ///< m, the body's bounding box
};

/// Imports and checks the surface (and, with [mesh] repair = true, checks the repaired copy), and
/// what every stage would refuse of it. Throws InputError when it cannot be meshed.
DesignSurfaceCheck check_design_surface(const Design& design);

} // namespace fibermold
