#pragma once
// Tracking curves (paper section V-A, Fig. 4): splines through the body along which simulated and
// target deformations are compared, sampled at points q_j with orthonormal frames A_j (tangent,
// normal, binormal as columns).

#include <vector>

#include <Eigen/Core>

namespace fibermold {

struct TrackingSamples {
  std::vector<Eigen::Vector3d> points; ///< q_j, m
  std::vector<Eigen::Matrix3d> frames; ///< A_j
  double weight_position = 1, weight_orientation = 0.1;
};

/// `samples` points uniformly along the Catmull–Rom spline through `points` (by arc length), with
/// frames transported along the curve without twist (double reflection).
TrackingSamples sample_tracking_curve(const std::vector<Eigen::Vector3d>& points, int samples, double weight_position,
                                      double weight_orientation);

} // namespace fibermold
