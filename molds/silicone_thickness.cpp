#include "molds/silicone_thickness.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <unordered_map>

#include <Eigen/Geometry>
#include <fmt/format.h>

namespace fibermold {

namespace {

/// The polylines' points in a horizontal grid (seen along pull) of `cell`-sized buckets.
class ShadowGrid {
public:
  /// `kept[f][k]`: point k of fiber f counts (its pieces count when both ends do).
  ShadowGrid(const std::vector<std::vector<Eigen::Vector3d>>& fibers, const std::vector<std::vector<bool>>& kept,
             const Eigen::Matrix3d& frame, double cell)
      : frame_(frame), cell_(cell)
  {
    for (std::size_t f = 0; f < fibers.size(); ++f)
      for (std::size_t k = 0; k + 1 < fibers[f].size(); ++k) {
        const std::vector<Eigen::Vector3d>& line = fibers[f];
        if (!kept[f][k] || !kept[f][k + 1]) continue;
        // Points every quarter cell along each piece: the shadow's distance to within an eighth.
        const int n = std::max(1, static_cast<int>(std::ceil((line[k + 1] - line[k]).norm() / (cell / 4))));
        for (int i = 0; i < n; ++i) {
          const Eigen::Vector3d p = frame_ * (line[k] + (line[k + 1] - line[k]) * (static_cast<double>(i) / n));
          buckets_[key(p)].push_back(p);
        }
      }
  }
  /// The lowest height of a point whose shadow lies within `reach` (≤ cell) of q's, or +∞.
  double lowest_within(const Eigen::Vector3d& world, double reach) const
  {
    const Eigen::Vector3d q = frame_ * world;
    double lowest = HUGE_VAL;
    const long i = cell_of(q.x()), j = cell_of(q.y());
    for (long a = i - 1; a <= i + 1; ++a)
      for (long b = j - 1; b <= j + 1; ++b)
        if (const auto it = buckets_.find(pack(a, b)); it != buckets_.end())
          for (const Eigen::Vector3d& p : it->second)
            if ((p.head<2>() - q.head<2>()).norm() <= reach) lowest = std::min(lowest, p.z());
    return lowest;
  }

private:
  long cell_of(double v) const { return static_cast<long>(std::floor(v / cell_)); }
  static long long pack(long a, long b)
  {
    return (static_cast<long long>(a) << 32) ^ static_cast<long long>(static_cast<unsigned>(b));
  }
  long long key(const Eigen::Vector3d& p) const { return pack(cell_of(p.x()), cell_of(p.y())); }

  Eigen::Matrix3d frame_;
  double cell_;
  std::unordered_map<long long, std::vector<Eigen::Vector3d>> buckets_;
};

} // namespace

std::vector<bool> beyond_skin_ends(const std::vector<Eigen::Vector3d>& line, const ExitStretches& exits)
{
  std::vector<bool> beyond(line.size(), true);
  if (line.empty()) return beyond;
  std::vector<double> s(line.size(), 0);
  for (std::size_t k = 1; k < line.size(); ++k) s[k] = s[k - 1] + (line[k] - line[k - 1]).norm();
  for (std::size_t k = 0; k < line.size(); ++k) beyond[k] = s[k] >= exits.first && s.back() - s[k] >= exits.last;
  return beyond;
}

SiliconeThickness silicone_thickness(const SurfaceMesh& groove_body, const SurfaceMesh& body,
                                     const std::vector<std::vector<Eigen::Vector3d>>& fibers, double radius,
                                     double muscle_radius, const Eigen::Vector3d& pull_in, double voxel,
                                     const std::vector<ExitStretches>& exits)
{
  SiliconeThickness out;
  const Eigen::Vector3d pull = pull_in.normalized();
  // Rows: two horizontal axes, then pull.
  Eigen::Matrix3d frame;
  frame.row(2) = pull.transpose();
  frame.row(0) = pull.unitOrthogonal().transpose();
  frame.row(1) = pull.cross(pull.unitOrthogonal()).transpose();

  // The points that count: not on an exit stretch.
  if (exits.size() != fibers.size())
    throw std::invalid_argument(
        fmt::format("silicone_thickness: {} exit stretches for {} fibers", exits.size(), fibers.size()));
  const SurfaceDistance skin(body.vertices, body.faces);
  std::vector<std::vector<bool>> kept;
  for (std::size_t f = 0; f < fibers.size(); ++f) kept.push_back(beyond_skin_ends(fibers[f], exits[f]));

  // Shot 1: the groove body's faces on a groove's walls (their shadow within a voxel and a half of
  // a groove's edge, at or above its bottom), and the silicone behind them. Not the lip within a
  // groove's radius below its mouth: where the groove leaves a sloping skin the cast tapers to an
  // edge there by design, and shot 2's silicone closes over it.
  const double reach = radius + 1.5 * voxel;
  const ShadowGrid shadows(fibers, kept, frame, reach);
  std::vector<Eigen::Index> walls;
  for (Eigen::Index f = 0; f < groove_body.num_faces(); ++f) {
    const Eigen::Vector3d c =
        (groove_body.vertices.row(groove_body.faces(f, 0)) + groove_body.vertices.row(groove_body.faces(f, 1)) +
         groove_body.vertices.row(groove_body.faces(f, 2)))
            .transpose() /
        3;
    if (c.dot(pull) >= shadows.lowest_within(c, reach) - radius - 1.5 * voxel && skin.ray_distance(c, pull) > radius)
      walls.push_back(f);
  }
  // The silicone behind a wall face: the median over a cone of rays (the inward normal and 8 rays
  // 30° off it, as the part checks measure walls) of how far each goes before it leaves the cast
  // through the skin, projected on the normal. A ray that leaves through another groove's wall
  // (crossing grooves leave a sheet between them that shot 2 encloses) or through a face more than
  // 53° off its direction (a corner, no wall) does not count.
  const SurfaceDistance cast(groove_body.vertices, groove_body.faces);
  const auto to_skin = [&](const Eigen::Vector3d& origin, const Eigen::Vector3d& dir) {
    const SurfaceDistance::Hit hit = cast.ray_hit(origin, dir, 1e-7);
    if (!std::isfinite(hit.distance) || hit.normal.dot(dir) < 0.6) return HUGE_VAL;
    return skin.closest(origin + hit.distance * dir).distance <= 1.5 * voxel ? hit.distance : HUGE_VAL;
  };
  const auto behind = [&](const Eigen::Vector3d& centre, const Eigen::Vector3d& inward) {
    const Eigen::Vector3d a = inward.unitOrthogonal(), b = inward.cross(a);
    const double tilt = M_PI / 6;
    std::vector<double> d{to_skin(centre, inward)};
    for (int k = 0; k < 8; ++k) {
      const double t = 2 * M_PI * k / 8;
      d.push_back(to_skin(centre, std::cos(tilt) * inward + std::sin(tilt) * (std::cos(t) * a + std::sin(t) * b)) *
                  std::cos(tilt));
    }
    std::nth_element(d.begin(), d.begin() + 4, d.end());
    return d[4];
  };
  for (const Eigen::Index f : walls) {
    const Eigen::Vector3d p0 = groove_body.vertices.row(groove_body.faces(f, 0)),
                          p1 = groove_body.vertices.row(groove_body.faces(f, 1)),
                          p2 = groove_body.vertices.row(groove_body.faces(f, 2));
    const Eigen::Vector3d n = (p1 - p0).cross(p2 - p0);
    if (!(n.norm() > 0)) continue;
    const Eigen::Vector3d centre = (p0 + p1 + p2) / 3, inward = -n.normalized();
    // One ray first; the cone only where it sees thin silicone.
    if (to_skin(centre, inward) >= kThickestMeasuredWeb) continue;
    if (const double t = behind(centre, inward); t < out.groove_web) out.groove_web = t, out.groove_web_at = centre;
  }

  // Shot 2: over each laid muscle (its axis radius − muscle_radius below the fiber's), up to the skin.
  for (std::size_t f = 0; f < fibers.size(); ++f) {
    const std::vector<Eigen::Vector3d>& line = fibers[f];
    for (std::size_t k = 0; k < line.size(); ++k) {
      if (!kept[f][k]) continue;
      const Eigen::Vector3d top = line[k] + (2 * muscle_radius - radius) * pull;
      const double d = skin.ray_distance(top, pull);
      if (std::isfinite(d) && d < out.overmold) out.overmold = d, out.overmold_at = top + d * pull;
    }
  }
  return out;
}

} // namespace fibermold
