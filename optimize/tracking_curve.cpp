#include "optimize/tracking_curve.hpp"

#include <Eigen/Geometry>

#include "sim/hermite_spline.hpp"

namespace fibermold {

namespace {

/// A unit vector perpendicular to t.
Eigen::Vector3d perpendicular(const Eigen::Vector3d& t)
{
  Eigen::Vector3d axis = Eigen::Vector3d::Zero();
  Eigen::Index least;
  t.cwiseAbs().minCoeff(&least);
  axis[least] = 1;
  return t.cross(axis).normalized();
}

} // namespace

TrackingSamples sample_tracking_curve(const std::vector<Eigen::Vector3d>& points, int samples, double weight_position,
                                      double weight_orientation)
{
  const HermiteSpline spline(points);
  // Arc-length table on a fine parameter grid, then samples at equal arc length.
  const int fine = 64 * spline.spans();
  std::vector<double> t(fine + 1), s(fine + 1, 0);
  for (int i = 0; i <= fine; ++i) t[i] = static_cast<double>(i) * spline.spans() / fine;
  for (int i = 1; i <= fine; ++i) s[i] = s[i - 1] + (spline.position(t[i]) - spline.position(t[i - 1])).norm();
  TrackingSamples out;
  out.weight_position = weight_position;
  out.weight_orientation = weight_orientation;
  std::size_t i = 1;
  Eigen::Vector3d normal = Eigen::Vector3d::UnitY();
  for (int j = 0; j < samples; ++j) {
    const double target = s.back() * j / std::max(1, samples - 1);
    while (i < s.size() - 1 && s[i] < target) ++i;
    const double a = s[i] > s[i - 1] ? (target - s[i - 1]) / (s[i] - s[i - 1]) : 0;
    const double tj = t[i - 1] + a * (t[i] - t[i - 1]);
    const Eigen::Vector3d q = spline.position(tj), tangent = spline.derivative(tj).normalized();
    if (j == 0) {
      normal = perpendicular(tangent);
    } else {
      // Double reflection (Wang et al. 2008): rotation-minimizing transport of the previous frame.
      const Eigen::Vector3d v1 = q - out.points.back();
      const Eigen::Vector3d& t0 = out.frames.back().col(0);
      const double c1 = v1.squaredNorm();
      if (c1 > 0) {
        const Eigen::Vector3d rL = normal - (2 / c1) * v1.dot(normal) * v1, tL = t0 - (2 / c1) * v1.dot(t0) * v1;
        const Eigen::Vector3d v2 = tangent - tL;
        const double c2 = v2.squaredNorm();
        normal = c2 > 0 ? Eigen::Vector3d(rL - (2 / c2) * v2.dot(rL) * v2) : rL;
      }
      normal = (normal - normal.dot(tangent) * tangent).normalized();
    }
    Eigen::Matrix3d A;
    A.col(0) = tangent;
    A.col(1) = normal;
    A.col(2) = tangent.cross(normal);
    out.points.push_back(q);
    out.frames.push_back(A);
  }
  return out;
}

} // namespace fibermold
