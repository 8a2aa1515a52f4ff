#include "molds/parting.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Geometry>

#include "core/units.hpp"

namespace fibermold {

namespace {

const double kFlat = std::sin(5 * units::degree); // |n·pull| below this: a wall parallel to pull

struct Facing {
  double height, area; ///< centroid along pull; area projected on the parting plane, m²
  bool up;             ///< n·pull > 0
};

std::vector<Facing> tilted_faces(const SurfaceMesh& m, const Eigen::Vector3d& pull)
{
  std::vector<Facing> out;
  for (Eigen::Index f = 0; f < m.num_faces(); ++f) {
    const Eigen::Vector3d a = m.vertices.row(m.faces(f, 0)), b = m.vertices.row(m.faces(f, 1)),
                          c = m.vertices.row(m.faces(f, 2));
    const Eigen::Vector3d n = (b - a).cross(c - a);
    const double area = n.norm() / 2;
    if (area <= 0) continue;
    const double up = n.normalized().dot(pull);
    if (std::abs(up) <= kFlat) continue;
    out.push_back({(a + b + c).dot(pull) / 3, area * std::abs(up), up > 0});
  }
  return out;
}

} // namespace

double undercut_area(const SurfaceMesh& cavity, const Eigen::Vector3d& point, const Eigen::Vector3d& pull_in)
{
  const Eigen::Vector3d pull = pull_in.normalized();
  const double h = point.dot(pull);
  double area = 0;
  for (const Facing& f : tilted_faces(cavity, pull))
    if (f.up ? f.height < h : f.height > h) area += f.area;
  return area;
}

double upright_share(const SurfaceMesh& cavity, const Eigen::Vector3d& point, const Eigen::Vector3d& pull_in,
                     double degrees)
{
  const Eigen::Vector3d pull = pull_in.normalized();
  const double h = point.dot(pull), sin_tol = std::sin(degrees * units::degree);
  double above = 0, upright = 0;
  for (Eigen::Index f = 0; f < cavity.num_faces(); ++f) {
    const Eigen::Vector3d a = cavity.vertices.row(cavity.faces(f, 0)), b = cavity.vertices.row(cavity.faces(f, 1)),
                          c = cavity.vertices.row(cavity.faces(f, 2));
    if ((a + b + c).dot(pull) / 3 <= h) continue;
    const Eigen::Vector3d n = (b - a).cross(c - a);
    const double area = n.norm() / 2;
    if (!(area > 0)) continue;
    above += area;
    if (std::abs(n.normalized().dot(pull)) <= sin_tol) upright += area;
  }
  return above > 0 ? upright / above : 0;
}

Parting choose_parting(const SurfaceMesh& cavity, const Eigen::Vector3d& pull_in, double ceiling)
{
  const Eigen::Vector3d pull = pull_in.normalized();
  std::vector<Facing> faces = tilted_faces(cavity, pull);
  std::sort(faces.begin(), faces.end(), [](const Facing& a, const Facing& b) { return a.height < b.height; });
  // U(h) = Σ up-facing area below h + Σ down-facing area above h, piecewise constant between
  // centroid heights; evaluate it on every interval below the ceiling.
  const Eigen::VectorXd heights = cavity.vertices * pull;
  const double lo = heights.minCoeff(), hi = std::max(lo + 1e-9, std::min(heights.maxCoeff(), ceiling));
  double down_above = 0;
  for (const Facing& f : faces)
    if (!f.up) down_above += f.area;
  // U on each interval between centroid heights, below the ceiling.
  struct Interval {
    double lo, hi, undercut;
  };
  std::vector<Interval> intervals;
  double up_below = 0, best = HUGE_VAL, start = lo;
  for (std::size_t k = 0; k <= faces.size(); ++k) {
    const double end = k < faces.size() ? std::min(faces[k].height, hi) : hi;
    if (end > start) {
      intervals.push_back({start, end, up_below + down_above});
      best = std::min(best, intervals.back().undercut);
    }
    if (k == faces.size() || end >= hi) break;
    (faces[k].up ? up_below : down_above) += faces[k].up ? faces[k].area : -faces[k].area;
    start = end;
  }
  // The best range: the widest run of intervals within kFacetUndercut of the least U. Heights whose
  // undercuts differ by less differ by a facet of the meshed level set, and the least of them alone
  // was a sliver: a 12 mm starfish's groove body has 0.0205 mm² from 0.6 to 6.6 mm and a hair less
  // about 0.4 mm, where its plane went, its lower half a 0.4 mm plate. (A slack of kUndercutWarning,
  // 1 mm², widened the coarse continuum robot's range of 0.57 mm² up its round flank to 0.94 mm²,
  // and the plane, 0.1 mm higher, met its end in a wedge of 0.00 mm.)
  constexpr double kFacetUndercut = 0.05 * units::mm2;
  double best_lo = lo, best_hi = hi, widest = -1;
  for (std::size_t i = 0, j = 0; i < intervals.size(); i = std::max(j, i + 1)) {
    for (j = i; j < intervals.size() && intervals[j].undercut <= best + kFacetUndercut;) ++j;
    if (j > i && intervals[j - 1].hi - intervals[i].lo > widest)
      best_lo = intervals[i].lo, best_hi = intervals[j - 1].hi, widest = best_hi - best_lo;
  }
  const double range_lo = std::max(best_lo, lo), range_hi = std::min(best_hi, hi);
  const double middle = (range_lo + range_hi) / 2;
  // A plane through vertices of the cavity (a polygonal body's ridge on its plane of symmetry) gives
  // the booleans coplanar edges, and the keys' unions then came out crossing themselves (an arm with
  // 10 vertices per ring): move it off them by 2 µm (up, then down, then twice that, …), within
  // the range of least undercut.
  constexpr double kOnPlane = 0.1e-6, kNudge = 2e-6;
  const double nudge = std::min(kNudge, (range_hi - range_lo) / 8);
  const auto on_vertices = [&](double h) { return ((heights.array() - h).abs() < kOnPlane).any(); };
  double h = middle;
  for (int k = 1; k <= 8 && nudge > 0 && on_vertices(h); ++k) h = middle + ((k + 1) / 2) * (k % 2 ? nudge : -nudge);
  const Eigen::Vector3d centre = cavity.vertices.colwise().mean().transpose();
  double undercut = intervals.back().undercut; // the plane's own U (a nudge may leave it on the run's top)
  for (auto i = intervals.rbegin(); i != intervals.rend(); ++i)
    if (i->lo <= h && h <= i->hi) undercut = i->undercut;
  return {centre + (h - centre.dot(pull)) * pull, pull, undercut};
}

PullSense pull_sense(const SurfaceMesh& body, const std::vector<std::vector<Eigen::Vector3d>>& fibers,
                     double groove_radius, const Eigen::Vector3d& pull_in)
{
  const Eigen::Vector3d pull = pull_in.normalized();
  double ceiling = HUGE_VAL;
  for (const auto& line : fibers)
    for (const Eigen::Vector3d& p : line) ceiling = std::min(ceiling, p.dot(pull) - groove_radius);
  const Parting parting = choose_parting(body, pull, ceiling);
  const Eigen::VectorXd heights = body.vertices * pull;
  const double h = parting.point.dot(pull);
  return {pull, parting, std::max(0.0, std::min(h - heights.minCoeff(), heights.maxCoeff() - h))};
}

std::vector<PullSense> choose_pull_sense(const SurfaceMesh& body,
                                         const std::vector<std::vector<Eigen::Vector3d>>& fibers, double groove_radius,
                                         const Eigen::Vector3d& pull, double undercut_slack)
{
  const PullSense given = pull_sense(body, fibers, groove_radius, pull),
                  reverse = pull_sense(body, fibers, groove_radius, -pull);
  const Eigen::VectorXd heights = body.vertices * given.pull;
  const double plate = std::max(kPlateDepth, kPlateShare * (heights.maxCoeff() - heights.minCoeff()));
  const bool reversed = given.thinner_half < plate && reverse.thinner_half >= given.thinner_half + kPlateDepth &&
                        reverse.parting.undercut_area <= given.parting.undercut_area + undercut_slack;
  return reversed ? std::vector{reverse, given} : std::vector{given, reverse};
}

} // namespace fibermold
