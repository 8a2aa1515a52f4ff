#pragma once
// A draft angle on the pull direction ([mold] draft_deg): each mold half's cavity widens toward
// the parting plane, so that the half slides off the cast part instead of dragging along walls
// parallel to pull. The cavity is grown outward by
//   r(h) = (reach − |h − parting|) · tan(angle),
// h a point's height along pull: nothing at the cavity's farthest point from the plane, reach ·
// tan(angle) at the plane, so that a wall parallel to pull leans out by the angle in both halves
// and the two halves meet without a step. Grooves are drafted by widening them upward instead (see
// groove_body), so that the muscle's tube at their bottom keeps its size. Both shots share one
// parting plane, so that the drafted shot 1 part fits the drafted shot 2 cavity.

#include <algorithm>
#include <cmath>

#include <Eigen/Core>

#include "mesh/surface_mesh.hpp"

namespace fibermold {

struct Draft {
  double parting = 0; ///< m, the parting plane's height along pull
  double reach = 0;   ///< m, the cavity's farthest height from it
  double slope = 0;   ///< tan of the draft angle
  double flat = 0;    ///< m: within this of the plane the walls stay parallel to pull

  double offset(double height) const
  {
    return std::max(0.0, reach - std::max(flat, std::abs(height - parting))) * slope;
  }
  double most() const { return std::max(0.0, reach - flat) * slope; }
};

/// The draft of `angle` (radians) for a cavity and the parting plane through `point` normal to pull,
/// on a grid of `voxel`.
inline Draft draft_for(const SurfaceMesh& cavity, const Eigen::Vector3d& pull, const Eigen::Vector3d& point,
                       double angle, double voxel)
{
  const Eigen::Vector3d u = pull.normalized();
  const Eigen::VectorXd heights = cavity.vertices * u;
  const double h = point.dot(u);
  return {h, std::max(heights.maxCoeff() - h, h - heights.minCoeff()), std::tan(angle), 2 * voxel};
}

} // namespace fibermold
