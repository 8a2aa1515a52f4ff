#pragma once
// Distance from points to a closed surface, and which side they are on: an AABB tree over its
// triangles (CGAL), built once. Used by the skin barrier of the optimizer (section V-B) and the
// clearance checks of collide, and ray casts for the wall thickness of mold parts.

#include <cmath>
#include <memory>

#include <Eigen/Core>

namespace fibermold {

class SurfaceDistance {
public:
  /// A closed, outward-oriented triangle surface; vertices not used by any face are ignored.
  SurfaceDistance(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces);
  ~SurfaceDistance();
  SurfaceDistance(const SurfaceDistance&) = delete;
  SurfaceDistance& operator=(const SurfaceDistance&) = delete;

  struct Closest {
    double distance;       ///< unsigned, to the nearest surface point
    Eigen::Vector3d point; ///< the nearest surface point
    bool inside;           ///< strictly inside the enclosed volume
    Eigen::Index face;     ///< the face (row of `faces`) the nearest point lies on
  };
  Closest closest(const Eigen::Vector3d& p) const;
  /// Inside the enclosed volume or within `tolerance` (m) of the surface: a point on the skin (a
  /// fiber's or a tracking curve's end) counts as in.
  bool holds(const Eigen::Vector3d& p, double tolerance) const
  {
    const Closest at = closest(p);
    return at.inside || at.distance <= tolerance;
  }
  /// Distance along the ray from `origin` in unit `direction` to the first surface point farther
  /// than `skip`; +∞ when it hits nothing.
  double ray_distance(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double skip = 0) const;
  struct Hit {
    double distance = HUGE_VAL;                       ///< +∞: no hit
    Eigen::Vector3d normal = Eigen::Vector3d::Zero(); ///< the hit face's unit outward normal
  };
  /// The same ray's first hit and the face it hits.
  Hit ray_hit(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double skip = 0) const;

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

} // namespace fibermold
