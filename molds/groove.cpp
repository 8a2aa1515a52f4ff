#include "molds/groove.hpp"

#include "mesh/surface_check.hpp"

#include "molds/level_set.hpp"

namespace fibermold {

GrooveBody groove_body(const SurfaceMesh& body, const std::vector<std::vector<Eigen::Vector3d>>& fibers, double radius,
                       const Eigen::Vector3d& pull_in, double voxel, double adaptivity)
{
  const Eigen::Vector3d pull = pull_in.normalized();
  const Eigen::VectorXd heights = body.vertices * pull;
  const double through = heights.maxCoeff() - heights.minCoeff() + 2 * radius;  // out of the body from anywhere
  LevelSet solid = LevelSet::from_mesh(body, voxel, pull);
  LevelSet grooves(voxel, pull);
  for (const auto& fiber : fibers) grooves.add_swept_tube(fiber, radius, through);
  solid.subtract(grooves);
  GrooveBody out;
  out.volume = solid.volume();
  out.adaptivity = adaptivity;
  out.mesh = solid.mesh(adaptivity);
  if (adaptivity > 0 && !check_surface(out.mesh).problems.empty()) {
    out.adaptivity = 0;
    out.mesh = solid.mesh(0);
  }
  return out;
}

} // namespace fibermold
