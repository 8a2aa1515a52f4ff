#include "molds/ports.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <fmt/format.h>

#include "mesh/surface_distance.hpp"

namespace fibermold {

namespace {

/// Up to `count` points of the cavity's top (within `band` of its highest point, z up) where a
/// hole of `radius` lands wholly on the top: every point of a circle of radius + `margin` around
/// it sees the top straight below. Wanted positions spread along the top region's longest
/// horizontal direction; each takes the nearest supported point of a grid over the region, else of
/// a ring around it twice the circle's radius wide: the top's vertices may all lie on its rim (a
/// face sloping out of the band, as the underside of a tapered arm whose next ring of vertices is
/// already higher than the band).
std::vector<Eigen::Vector3d> top_points(const SurfaceMesh& m, int count, double band, double radius, double margin)
{
  const double top = m.vertices.col(2).maxCoeff();
  std::vector<Eigen::Vector2d> region;
  for (Eigen::Index i = 0; i < m.num_vertices(); ++i)
    if (m.vertices(i, 2) >= top - band) region.push_back(m.vertices.row(i).head<2>().transpose());
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  for (const auto& p : region) centre += p / static_cast<double>(region.size());
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
  for (const auto& p : region) cov += (p - centre) * (p - centre).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(cov);
  const Eigen::Vector2d axis = eig.eigenvectors().col(1), across = eig.eigenvectors().col(0);
  double reach = 0, width = 0;
  for (const auto& p : region) {
    reach = std::max(reach, std::abs((p - centre).dot(axis)));
    width = std::max(width, std::abs((p - centre).dot(across)));
  }
  const SurfaceDistance surface(m.vertices, m.faces);
  const auto on_top = [&](const Eigen::Vector2d& xy) {
    const double d = surface.ray_distance({xy.x(), xy.y(), top + 1e-3}, -Eigen::Vector3d::UnitZ());
    return d <= 1e-3 + band;
  };
  const auto supported = [&](const Eigen::Vector2d& xy) {
    if (!on_top(xy)) return false;
    for (int k = 0; k < 12; ++k) {
      const double a = 2 * M_PI * k / 12;
      if (!on_top(xy + (radius + margin) * Eigen::Vector2d(std::cos(a), std::sin(a)))) return false;
    }
    return true;
  };
  const double step = std::max(radius, 0.25e-3);
  // The grid over the region first; its ring grown by 2 (radius + margin) only where the region's
  // own grid has no supported point.
  std::vector<Eigen::Vector2d> inner, ring;
  for (double s = -reach; s <= reach; s += step)
    for (double t = -width; t <= width; t += step) inner.push_back(centre + s * axis + t * across);
  const int grow = static_cast<int>(std::ceil(2 * (radius + margin) / step));
  for (int i = -grow; i <= grow + static_cast<int>(std::floor(2 * reach / step)); ++i)
    for (int j = -grow; j <= grow + static_cast<int>(std::floor(2 * width / step)); ++j) {
      const double s = -reach + i * step, t = -width + j * step;
      if (s < -reach || s > reach || t < -width || t > width) ring.push_back(centre + s * axis + t * across);
    }
  std::vector<Eigen::Vector3d> out;
  for (int k = 0; k < count; ++k) {
    const double t = count == 1 ? 0 : -0.5 + static_cast<double>(k) / (count - 1);  // over the middle half
    const Eigen::Vector2d wanted = centre + t * reach * axis;
    for (std::vector<Eigen::Vector2d>* grid : {&inner, &ring}) {
      std::sort(grid->begin(), grid->end(), [&](const auto& a, const auto& b) { return (a - wanted).norm() < (b - wanted).norm(); });
      const auto found = std::find_if(grid->begin(), grid->end(), [&](const Eigen::Vector2d& xy) {
        const bool apart = std::all_of(out.begin(), out.end(), [&](const Eigen::Vector3d& q) { return (q.head<2>() - xy).norm() >= 2 * (radius + margin); });
        return apart && supported(xy);
      });
      if (found != grid->end()) {
        out.emplace_back(found->x(), found->y(), top - surface.ray_distance({found->x(), found->y(), top + 1e-3}, -Eigen::Vector3d::UnitZ()) + 1e-3);
        break;
      }
    }
  }
  return out;
}

/// The cavity in a frame where pull is +z (R: body frame to it), or upside down.
SurfaceMesh in_frame(SurfaceMesh m, const Eigen::Matrix3d& R, bool flip)
{
  m.vertices = (m.vertices * R.transpose()).eval();
  if (flip) {
    m.vertices.col(2) *= -1;
    m.faces.col(1).swap(m.faces.col(2));
  }
  return m;
}

} // namespace

Ports cavity_ports(const SurfaceMesh& cavity, const Eigen::Vector3d& pull, double sprue_diameter, int vents,
                   double vent_diameter, double margin, const std::string& shot)
{
  const Eigen::Matrix3d R = Eigen::Quaterniond::FromTwoVectors(pull.normalized(), Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const double band = 0.5e-3;
  const std::vector<Eigen::Vector3d> lowest = top_points(in_frame(cavity, R, true), 1, band, sprue_diameter / 2, margin);
  if (lowest.empty())
    throw std::runtime_error(fmt::format(
        "{}: no flat spot at the cavity's bottom (within {:.1f} mm of its lowest point, seen along the pull direction) "
        "takes the sprue: it needs a circle of {:.1f} mm across ([mold] sprue_diameter + 2 × [export] min_wall); make "
        "sprue_diameter smaller or give the body a wider flat bottom",
        shot, band / 1e-3, (sprue_diameter + 2 * margin) / 1e-3));
  Ports out;
  const Eigen::Vector3d& s = lowest.front();
  out.sprues.push_back({R.transpose() * Eigen::Vector3d(s.x(), s.y(), -s.z()), sprue_diameter, false});
  if (vents > 0)
    for (const Eigen::Vector3d& v : top_points(in_frame(cavity, R, false), vents, band, vent_diameter / 2, margin))
      out.vents.push_back({R.transpose() * v, vent_diameter, true});
  return out;
}

FillPlan plan_fill(const VoxelRegion& region, Ports ports, double sprue_diameter, double vent_diameter, bool sprue_from_above)
{
  const Eigen::Vector3d up = region.axes.col(2);
  const auto voxel_of = [&](const Eigen::Vector3d& p) -> Eigen::Vector3i { return region.grid(p).array().round().cast<int>(); };
  // From above: straight over the part's lowest voxel, where its column's highest voxel meets the mold.
  const auto sprue_at = [&](const Eigen::Vector3d& lowest) -> Port {
    if (!sprue_from_above) return {lowest - region.voxel / 2 * up, sprue_diameter, false};
    const Eigen::Vector3i v = voxel_of(lowest);
    int top = v.z();
    for (int k = v.z(); k < region.size.z(); ++k)
      if (region.contains(v.x(), v.y(), k)) top = k;
    return {region.centre(v.x(), v.y(), top) + region.voxel / 2 * up, sprue_diameter, true};
  };
  FillPlan plan{std::move(ports), {}};
  for (;;) {
    plan.fill = simulate_fill(region, plan.ports.sprues, plan.ports.vents);
    const FillResult& f = plan.fill;
    bool added = false;
    double left = f.fill_volume - f.reachable_volume - f.crevice_volume;
    for (const AirPocket& part : f.unreachable) {
      if (left <= kTrappedAirTolerance || static_cast<int>(plan.ports.sprues.size()) >= kMaxSprues) break;
      plan.ports.sprues.push_back(sprue_at(part.at));
      left -= part.volume;
      added = true;
    }
    if (added) continue;  // the new sprues' air first
    left = f.trapped_volume;
    for (const AirPocket& pocket : f.pockets) {
      if (left <= kTrappedAirTolerance || static_cast<int>(plan.ports.vents.size()) >= kMaxVents) break;
      if (!pocket.ventable) continue;
      plan.ports.vents.push_back({pocket.at + region.voxel / 2 * up, vent_diameter, true});
      left -= pocket.volume;
      added = true;
    }
    if (!added) return plan;
  }
}

} // namespace fibermold
