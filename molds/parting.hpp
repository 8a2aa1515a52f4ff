#pragma once
// The parting plane of a two-part mold, normal to the pull direction: the halves come apart along
// ±pull. A face of the cavity is an undercut when the half that holds it cannot slide off it: in
// the upper half (pulled along +pull) a face whose outward normal points down (n·pull < 0), in the
// lower half one whose normal points up. Undercut area is measured projected on the parting plane
// (the area the mold cannot slide past), faces counted by their centroid and within 5° of parallel
// to pull not at all, so that the facets of a voxelized wall do not count. "auto" picks the height
// with the least undercut area, in the middle of the best range.

#include <Eigen/Core>

#include "mesh/surface_mesh.hpp"

namespace fibermold {

struct Parting {
  Eigen::Vector3d point, normal; ///< normal = pull (unit)
  double undercut_area = 0;      ///< m², projected on the plane
};

/// Undercut area of `cavity` for the plane.
double undercut_area(const SurfaceMesh& cavity, const Eigen::Vector3d& point, const Eigen::Vector3d& pull);

/// The share of the cavity's area above the plane (the upper half's contact) that lies within
/// `degrees` of parallel to pull: walls that the half slides along as it comes off, which a draft
/// would lean.
double upright_share(const SurfaceMesh& cavity, const Eigen::Vector3d& point, const Eigen::Vector3d& pull,
                     double degrees);

/// The plane normal to `pull` with the least undercut area.
Parting choose_parting(const SurfaceMesh& cavity, const Eigen::Vector3d& pull);

} // namespace fibermold
