#pragma once
// Bodies and routes for the clearance tests: muscles 3 mm across, 1 mm clearance, so centre lines
// at least 4 mm apart and 2.5 mm inside the skin.

#include <string>
#include <vector>

#include "../primitives.hpp"
#include "core/units.hpp"
#include "mesh/surface_distance.hpp"
#include "optimize/routing_problem.hpp"

namespace fibermold::test {

inline constexpr double kRadius = 1.5e-3, kClearance = 1e-3, kSamplesPerLength = 4000;

inline Eigen::Vector3d mm(double x, double y, double z) { return Eigen::Vector3d(x, y, z) * units::mm; }

inline Route route(std::string name, const std::vector<Eigen::Vector3d>& points)
{
  const HermiteSpline s(points);
  return {std::move(name), s.points(), s.tangents()};
}

struct Body {
  SurfaceMesh surface;
  SurfaceDistance skin;
  Body(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi)
      : surface(test::box(lo, hi, 4)), skin(surface.vertices, surface.faces)
  {
  }
};

} // namespace fibermold::test
