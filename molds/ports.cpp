#include "molds/ports.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <stdexcept>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <fmt/format.h>

#include "core/units.hpp"
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
    const double t = count == 1 ? 0 : -0.5 + static_cast<double>(k) / (count - 1); // over the middle half
    const Eigen::Vector2d wanted = centre + t * reach * axis;
    for (std::vector<Eigen::Vector2d>* grid : {&inner, &ring}) {
      std::sort(grid->begin(), grid->end(),
                [&](const auto& a, const auto& b) { return (a - wanted).norm() < (b - wanted).norm(); });
      const auto found = std::find_if(grid->begin(), grid->end(), [&](const Eigen::Vector2d& xy) {
        const bool apart = std::all_of(out.begin(), out.end(), [&](const Eigen::Vector3d& q) {
          return (q.head<2>() - xy).norm() >= 2 * (radius + margin);
        });
        return apart && supported(xy);
      });
      if (found != grid->end()) {
        out.emplace_back(found->x(), found->y(),
                         top - surface.ray_distance({found->x(), found->y(), top + 1e-3}, -Eigen::Vector3d::UnitZ()) +
                             1e-3);
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
  const Eigen::Matrix3d R =
      Eigen::Quaterniond::FromTwoVectors(pull.normalized(), Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const double band = 0.5e-3;
  const std::vector<Eigen::Vector3d> lowest =
      top_points(in_frame(cavity, R, true), 1, band, sprue_diameter / 2, margin);
  if (lowest.empty())
    throw std::runtime_error(fmt::format(
        "{}: no flat spot at the cavity's bottom (within {:.1f} mm of its lowest point, seen along the pull direction) "
        "takes the sprue: it needs a circle of {:.1f} mm across ([mold] sprue_diameter + 2 × [export] min_wall); make "
        "sprue_diameter smaller or give the body a wider flat bottom",
        shot, band / units::mm, (sprue_diameter + 2 * margin) / units::mm));
  Ports out;
  const Eigen::Vector3d& s = lowest.front();
  out.sprues.push_back({R.transpose() * Eigen::Vector3d(s.x(), s.y(), -s.z()), sprue_diameter, false});
  if (vents > 0)
    for (const Eigen::Vector3d& v : top_points(in_frame(cavity, R, false), vents, band, vent_diameter / 2, margin))
      out.vents.push_back({R.transpose() * v, vent_diameter, true});
  return out;
}

namespace {

/// Where holes can meet the cavity from outside along ±pull.
class HoleSites {
public:
  HoleSites(const VoxelRegion& region, const SurfaceMesh& cavity, double min_wall)
      : region_(region), surface_(cavity.vertices, cavity.faces), min_wall_(min_wall)
  {
    const Eigen::VectorXd h = cavity.vertices * region.axes.col(2);
    lowest_ = h.minCoeff();
    highest_ = h.maxCoeff();
  }

  /// The site for a hole of `diameter` near `near` (m): the candidate on a grid of the region's
  /// voxel within 3 mm whose column meets the fill region first and where the skin under each
  /// point of the hole's rim lies within tan 35° of its radius of the mouth's height (the mold
  /// between the hole's wall and a skin sloping more steeply would be a knife edge) or 2 mm or
  /// more below it (the hole's edge passes over a groove's rib or the body's side, and its bottom
  /// stands on thick mold); for a vent the highest such site, for a sprue the nearest.
  std::optional<Port> near(const Eigen::Vector3d& near, double diameter, bool upward, bool highest,
                           const Ports& placed) const
  {
    // Within 3 mm first; farther out where nothing nearer takes the hole (the holes already placed
    // crowd it on a flat top, or the skin is too steep).
    for (const double search : {3e-3, 6e-3, 12e-3})
      if (auto site = within(near, diameter, upward, highest, placed, search)) return site;
    return std::nullopt;
  }

private:
  std::optional<Port> within(const Eigen::Vector3d& near, double diameter, bool upward, bool highest,
                             const Ports& placed, double search) const
  {
    const Eigen::Vector3d up = region_.axes.col(2), u = region_.axes.col(0), v = region_.axes.col(1);
    const double r = diameter / 2, step = region_.voxel;
    std::optional<Port> best;
    double best_score = 0;
    const int n = static_cast<int>(std::ceil(search / step));
    for (int a = -n; a <= n; ++a)
      for (int b = -n; b <= n; ++b) {
        if (std::hypot(a, b) * step > search) continue;
        const Eigen::Vector3d c = near + step * (a * u + b * v);
        if (crowded(c, diameter, placed)) continue;
        const auto h = skin(c, upward);
        if (!h || !opens_on_fill(c, upward)) continue;
        // A vent as high as it goes (by the voxel) but not above the top it is for (higher skin is
        // other air's), then as near; a sprue as near.
        const double height = upward ? *h : -*h; // the mouth's height along pull
        if (highest && height > near.dot(up) + step) continue;
        const double score = (highest ? std::round(height / step) * 1e6 : 0.0) - std::hypot(a, b);
        if (best && score <= best_score) continue;
        // Each point of the rim: on a skin within 35° of level, or over a drop of 2 mm or more
        // (a groove's rib, the body's side) where the hole's bottom stands on thick mold.
        double deepest = *h; // of the level skin under the rim, in the hole's "along"
        bool ok = true;
        for (int k = 0; k < 12 && ok; ++k) {
          const double t = 2 * M_PI * k / 12;
          const auto hk = skin(c + r * (std::cos(t) * u + std::sin(t) * v), upward);
          const double drop = hk ? *h - *hk : HUGE_VAL; // away from outside
          const bool level = std::abs(drop) <= std::tan(35 * units::degree) * r;
          ok = level || drop >= 2e-3;
          if (level) deepest = std::min(deepest, *hk);
        }
        if (!ok || rises_beside(c, r, *h, upward) || knife_edge_beside(c, r, deepest - 0.5e-3, upward)) continue;
        const Eigen::Vector3d at = c - (c.dot(up)) * up + (upward ? *h : -*h) * up;
        // The cut reaches 0.5 mm past the deepest level skin under the rim.
        best = Port{at, diameter, upward, *h - deepest + 0.5e-3};
        best_score = score;
      }
    return best;
  }

  /// The skin rises beside the hole: within min_wall of its wall (a ring of 16 points at radius
  /// r + min_wall), above the mouth's height `h` by more than a 35° slope: the hole runs down past
  /// a wall of the cavity (a slot's side, as a sprue to a slot's floor through the mold's rib in
  /// it), and the mold between them would be thinner than the printer holds (the gripper finger's
  /// shot 2: a wall of 0.27 mm beside a sprue at a slot floor, until session 25).
  bool rises_beside(const Eigen::Vector3d& c, double r, double h, bool upward) const
  {
    const Eigen::Vector3d u = region_.axes.col(0), v = region_.axes.col(1);
    const double ring = r + min_wall_;
    for (int k = 0; k < 16; ++k) {
      const double t = 2 * M_PI * k / 16;
      const auto hk = skin(c + ring * (std::cos(t) * u + std::sin(t) * v), upward);
      if (hk && h - *hk < -std::tan(35 * units::degree) * ring) return true;
    }
    return false;
  }

  /// Beside the cut, the cavity comes back within min_wall of its wall, above the cut's bottom
  /// (`bottom`, in the hole's "along"): along each of 48 directions out from the axis, at radii r to
  /// r + min_wall by quarters of min_wall, the skin rises from the lowest it has been on the way out
  /// by more than a 35° slope. The mold left between the cut and that cavity is a knife edge or a
  /// fin thinner than the printer holds: the rim's 12 points and the ring of rises_beside pass over
  /// a slit between two ribs narrower than the hole, whose roof rises past the rim (the walking
  /// robot's shot 1, session 43: a vent over a 0.2 mm slit under a crossing groove left 0.09 mm).
  bool knife_edge_beside(const Eigen::Vector3d& c, double r, double bottom, bool upward) const
  {
    const Eigen::Vector3d u = region_.axes.col(0), v = region_.axes.col(1);
    const double slope = std::tan(35 * units::degree);
    for (int k = 0; k < 48; ++k) {
      const double t = 2 * M_PI * k / 48;
      const Eigen::Vector3d out = std::cos(t) * u + std::sin(t) * v;
      double lowest = HUGE_VAL, lowest_at = r;
      for (int q = 0; q <= 4; ++q) {
        const double rho = r + min_wall_ * q / 4;
        const auto hk = skin(c + rho * out, upward);
        if (!hk) break; // outside the body: the mold beyond is the block's
        if (*hk > bottom && *hk - lowest > slope * (rho - lowest_at)) return true;
        if (*hk < lowest) lowest = *hk, lowest_at = rho;
      }
    }
    return false;
  }

  /// A hole at c would come within 1 mm of a hole already placed (seen along pull): overlapping
  /// cylinders leave the booleans slivers, and a wall between them thinner than a printer holds.
  bool crowded(const Eigen::Vector3d& c, double diameter, const Ports& placed) const
  {
    const Eigen::Vector3d up = region_.axes.col(2);
    const auto apart = [&](const Port& p) {
      const Eigen::Vector3d d = p.mouth - c;
      return (d - d.dot(up) * up).norm() >= (p.diameter + diameter) / 2 + 1e-3;
    };
    return !(std::all_of(placed.sprues.begin(), placed.sprues.end(), apart) &&
             std::all_of(placed.vents.begin(), placed.vents.end(), apart));
  }

  /// The skin's first point along ±pull from outside over `p`: its height as "along" from outside
  /// (for a hole from below, the negated height), or none.
  std::optional<double> skin(const Eigen::Vector3d& p, bool upward) const
  {
    const Eigen::Vector3d up = region_.axes.col(2);
    const double from = upward ? highest_ + 1e-3 : lowest_ - 1e-3;
    const Eigen::Vector3d origin = p - p.dot(up) * up + from * up;
    const double d = surface_.ray_distance(origin, upward ? -up : up);
    if (!std::isfinite(d)) return std::nullopt;
    return upward ? from - d : -(from + d);
  }
  /// The first cell that the column over (under) p meets from outside is fill.
  bool opens_on_fill(const Eigen::Vector3d& p, bool upward) const
  {
    const Eigen::Vector3d g = region_.grid(p);
    const int i = static_cast<int>(std::lround(g.x())), j = static_cast<int>(std::lround(g.y()));
    for (int k = upward ? region_.size.z() - 1 : 0; k >= 0 && k < region_.size.z(); k += upward ? -1 : 1)
      if (const auto c = region_.cell(i, j, k); c != VoxelRegion::mold) return c == VoxelRegion::fill;
    return false;
  }

  const VoxelRegion& region_;
  SurfaceDistance surface_;
  double min_wall_ = 0; ///< m, the printer's thinnest wall
  double lowest_ = 0, highest_ = 0;
};

} // namespace

FillPlan plan_fill(const VoxelRegion& region, const SurfaceMesh& cavity, Ports ports, double sprue_diameter,
                   double vent_diameter, double min_wall, bool sprue_from_above, const VoxelRegion* overmold,
                   double tolerance)
{
  const HoleSites sites(region, cavity, min_wall);
  const auto at_a_groove = [&](const AirPocket& p) {
    if (!overmold || !p.thin) return false;
    const Eigen::Vector3i g = overmold->grid(p.at).array().round().cast<int>();
    for (int k = -2; k <= 2; ++k)
      for (int j = -2; j <= 2; ++j)
        for (int i = -2; i <= 2; ++i)
          if (overmold->contains(g.x() + i, g.y() + j, g.z() + k)) return true;
    return false;
  };
  FillPlan plan{std::move(ports), {}};
  double before = HUGE_VAL;
  for (;;) {
    const auto started = std::chrono::steady_clock::now();
    plan.fill = simulate_fill(region, plan.ports.sprues, plan.ports.vents);
    plan.simulation_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    ++plan.simulations;
    FillResult& f = plan.fill;
    for (const AirPocket& p : f.pockets)
      if (at_a_groove(p)) f.overmolded_air_volume += p.volume;
    std::erase_if(f.pockets, at_a_groove);
    f.trapped_volume = 0;
    for (const AirPocket& p : f.pockets) f.trapped_volume += p.volume;
    bool added = false;
    double left = f.fill_volume - f.reachable_volume - f.crevice_volume;
    for (const AirPocket& part : f.unreachable) {
      if (left <= tolerance || static_cast<int>(plan.ports.sprues.size()) >= kMaxSprues) break;
      if (const auto sprue = sites.near(part.at, sprue_diameter, sprue_from_above, false, plan.ports))
        plan.ports.sprues.push_back(*sprue), added = true;
      left -= part.volume;
    }
    if (added) continue; // the new sprues' air first
    // Vents while they let out air: each pocket's gets the highest site near its top.
    if (f.trapped_volume >= before) return plan;
    before = f.trapped_volume;
    left = f.trapped_volume;
    for (const AirPocket& pocket : f.pockets) {
      if (left <= tolerance || static_cast<int>(plan.ports.vents.size()) >= kMaxVents) break;
      if (!pocket.ventable) continue;
      if (const auto vent = sites.near(pocket.at, vent_diameter, true, true, plan.ports))
        plan.ports.vents.push_back(*vent), added = true;
      left -= pocket.volume;
    }
    // The parts nested in a pocket that is being vented would be sealed next: vent them now.
    if (added)
      for (const AirPocket& part : f.nested) {
        if (static_cast<int>(plan.ports.vents.size()) >= kMaxVents) break;
        if (!part.ventable || at_a_groove(part)) continue;
        if (const auto vent = sites.near(part.at, vent_diameter, true, true, plan.ports))
          plan.ports.vents.push_back(*vent);
      }
    if (!added) return plan;
  }
}

} // namespace fibermold
