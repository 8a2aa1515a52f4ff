#pragma once
// The parting plane of a two-part mold, normal to the pull direction: the halves come apart along
// ±pull. A face of the cavity is an undercut when the half that holds it cannot slide off it: in
// the upper half (pulled along +pull) a face whose outward normal points down (n·pull < 0), in the
// lower half one whose normal points up. Undercut area is measured projected on the parting plane
// (the area the mold cannot slide past), faces counted by their centroid and within 5° of parallel
// to pull not at all, so that the facets of a voxelized wall do not count. "auto" picks the height
// with the least undercut area, in the middle of the best range, and the sense of the pull that does
// not leave one half a plate (choose_pull_sense).

#include <cmath>
#include <vector>

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

/// The plane normal to `pull` with the least undercut area (within a facet's, 0.05 mm²: in the middle
/// of the widest run of heights that near the least), at a height along pull of at most `ceiling`
/// (m; shot 1's grooves open along pull, so its plane passes below their bottoms).
Parting choose_parting(const SurfaceMesh& cavity, const Eigen::Vector3d& pull, double ceiling = HUGE_VAL);

/// Shot 1's plane for one sense of the pull: below every groove's bottom (each fiber's lowest point
/// along pull less the groove's radius), at the height of the body's least undercut there; and how
/// deep the shallower half's share of the cavity is, the plane's distance to the body's nearer end.
struct PullSense {
  Eigen::Vector3d pull; ///< unit
  Parting parting;
  double thinner_half = 0; ///< m
};
PullSense pull_sense(const SurfaceMesh& body, const std::vector<std::vector<Eigen::Vector3d>>& fibers,
                     double groove_radius, const Eigen::Vector3d& pull);

/// An undercut below this projected area (m²) is facets of the meshed level set, not a shape the
/// mold holds on to: it is logged but not warned about.
inline constexpr double kUndercutWarning = 1e-6;

/// A half whose share of the cavity is shallower than both of these is a plate (the gripper finger's
/// lower half once held 0.44 mm of its 20 mm): 1 mm, or a fifth of the body's extent along the pull.
inline constexpr double kPlateDepth = 1e-3, kPlateShare = 0.2;

/// The sense of the pull a mold maker would choose, given `pull`: its reverse when shot 1's shallower
/// half is a plate with `pull` and at least kPlateDepth deeper with the reverse, at most `undercut_slack`
/// (m²) more undercut. Both senses are returned, the chosen first.
std::vector<PullSense> choose_pull_sense(const SurfaceMesh& body,
                                         const std::vector<std::vector<Eigen::Vector3d>>& fibers, double groove_radius,
                                         const Eigen::Vector3d& pull, double undercut_slack);

} // namespace fibermold
