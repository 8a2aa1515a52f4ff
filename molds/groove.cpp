#include "molds/groove.hpp"

#include <algorithm>
#include <cmath>

#include "mesh/surface_check.hpp"

#include "molds/level_set.hpp"

namespace fibermold {

namespace {

/// The polyline with the fewest points that stays within `tolerance` of it (Douglas–Peucker):
/// straight stretches become one long piece of the sweep.
std::vector<Eigen::Vector3d> simplified(const std::vector<Eigen::Vector3d>& line, double tolerance)
{
  if (line.size() < 3) return line;
  std::vector<bool> keep(line.size(), false);
  keep.front() = keep.back() = true;
  std::vector<std::pair<std::size_t, std::size_t>> spans{{0, line.size() - 1}};
  while (!spans.empty()) {
    const auto [a, b] = spans.back();
    spans.pop_back();
    const Eigen::Vector3d ab = line[b] - line[a];
    double worst = 0;
    std::size_t at = a;
    for (std::size_t i = a + 1; i < b; ++i) {
      const double t =
          ab.squaredNorm() > 0 ? std::clamp((line[i] - line[a]).dot(ab) / ab.squaredNorm(), 0.0, 1.0) : 0.0;
      if (const double d = (line[i] - line[a] - t * ab).norm(); d > worst) worst = d, at = i;
    }
    if (worst <= tolerance) continue;
    keep[at] = true;
    spans.emplace_back(a, at);
    spans.emplace_back(at, b);
  }
  std::vector<Eigen::Vector3d> out;
  for (std::size_t i = 0; i < line.size(); ++i)
    if (keep[i]) out.push_back(line[i]);
  return out;
}

/// The solid's mesh: adaptive unless that one is not a valid solid, then uniform.
GrooveBody meshed(const LevelSet& solid, double adaptivity)
{
  GrooveBody out;
  out.volume = solid.volume();
  out.mesh = solid.mesh(adaptivity, &out.adaptivity);
  if (adaptivity > 0 && !check_surface(out.mesh).problems.empty()) {
    out.adaptivity = 0;
    out.mesh = solid.mesh(0);
  }
  return out;
}

} // namespace

GrooveBody groove_body(const SurfaceMesh& body, const std::vector<std::vector<Eigen::Vector3d>>& fibers, double radius,
                       const Eigen::Vector3d& pull_in, double voxel, double adaptivity, const Draft* draft,
                       GrooveBody* solid_body)
{
  const Eigen::Vector3d pull = pull_in.normalized();
  const Eigen::VectorXd heights = body.vertices * pull;
  // Out of the (drafted) body from anywhere.
  const double through = heights.maxCoeff() - heights.minCoeff() + 2 * radius + (draft ? 2 * draft->most() : 0);
  // A drafted body is voxelized with room outside for its growth.
  const double half_width = 3, exterior = draft ? half_width + std::ceil(draft->most() / voxel) + 1 : 0;
  LevelSet solid = LevelSet::from_mesh(body, voxel, pull, half_width, exterior);
  if (draft) solid.grow([&](double h) { return draft->offset(h); }, draft->most());
  if (solid_body) *solid_body = meshed(solid, adaptivity);
  LevelSet grooves(voxel, pull);
  for (const auto& fiber : fibers)
    grooves.add_swept_tube(simplified(fiber, voxel / 10), radius, through, draft ? draft->slope : 0);
  solid.subtract(grooves);
  return meshed(solid, adaptivity);
}

FillRegions fill_regions(const SurfaceMesh& cavity, const std::vector<std::vector<Eigen::Vector3d>>& fibers,
                         double radius, double muscle_radius, const Eigen::Vector3d& pull_in, double voxel,
                         double taper)
{
  const Eigen::Vector3d pull = pull_in.normalized();
  const Eigen::VectorXd heights = cavity.vertices * pull;
  const double through = heights.maxCoeff() - heights.minCoeff() + 2 * radius;
  LevelSet body = LevelSet::from_mesh(cavity, voxel, pull);
  LevelSet grooves(voxel, pull), muscles(voxel, pull);
  for (const auto& fiber : fibers) {
    grooves.add_swept_tube(simplified(fiber, voxel / 10), radius, through, taper);
    std::vector<Eigen::Vector3d> laid = fiber;
    for (Eigen::Vector3d& p : laid) p -= (radius - muscle_radius) * pull;
    muscles.add_swept_tube(simplified(laid, voxel / 10), muscle_radius, 0);
  }
  FillRegions out;
  LevelSet grooved = body.copy(), cut = grooves.copy();
  grooved.subtract(cut);
  out.shot1 = grooved.voxels();
  LevelSet space = body.copy();
  space.intersect(grooves);
  space.subtract(muscles);
  out.shot2 = space.voxels(&body); // the rest of the body is cured silicone and muscle
  return out;
}

double fill_voxel(double voxel, double radius) { return std::max(voxel, radius / 4); }

} // namespace fibermold
