#include "molds/grid_budget.hpp"

#include <cmath>

#include <Eigen/Geometry>
#include <fmt/format.h>

#include "core/units.hpp"
#include "molds/groove.hpp"

namespace fibermold {

GridEstimate estimate_grids(const SurfaceMesh& body, double voxel, double radius,
                            const std::vector<std::vector<Eigen::Vector3d>>& fibers)
{
  double groove_length = 0;
  for (const auto& line : fibers)
    for (std::size_t k = 1; k < line.size(); ++k) groove_length += (line[k] - line[k - 1]).norm();
  double area = 0;
  for (Eigen::Index f = 0; f < body.faces.rows(); ++f) {
    const Eigen::Vector3d a = body.vertices.row(body.faces(f, 0)), b = body.vertices.row(body.faces(f, 1)),
                          c = body.vertices.row(body.faces(f, 2));
    area += (b - a).cross(c - a).norm() / 2;
  }
  area += 2 * M_PI * radius * groove_length;
  const Eigen::Vector3d size = body.vertices.colwise().maxCoeff() - body.vertices.colwise().minCoeff();
  const double cell = fill_voxel(voxel, radius);
  return {6 * area / (voxel * voxel), (size.array() / cell + 3).prod()};
}

namespace {

/// `v` rounded up at two significant figures: a voxel said as "0.34 mm or more" must itself pass.
double round_up_2g(double v)
{
  const double step = std::pow(10.0, std::floor(std::log10(v)) - 1);
  return std::ceil(v / step * (1 - 1e-12)) * step;
}

} // namespace

std::optional<std::string> grid_budget_problem(const GridEstimate& e, double voxel)
{
  if (e.band_voxels > kMaxBandVoxels)
    return fmt::format("a {:.3g} mm voxel would carve the skin and the grooves in about {:.3g} million voxels, more "
                       "than the {:.0f} million "
                       "that carve in minutes; raise [mold].voxel to {:.2g} mm or more (or check the muscle's diameter "
                       "and [design].units)",
                       voxel / units::mm, e.band_voxels / 1e6, kMaxBandVoxels / 1e6,
                       round_up_2g(voxel * std::sqrt(e.band_voxels / kMaxBandVoxels) / units::mm));
  if (e.fill_voxels > kMaxFillVoxels)
    return fmt::format(
        "the fill simulation would sample the body on about {:.3g} million voxels, more than {:.0f} million; raise "
        "[mold].voxel",
        e.fill_voxels / 1e6, kMaxFillVoxels / 1e6);
  return std::nullopt;
}

} // namespace fibermold
