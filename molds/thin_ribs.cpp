#include "molds/thin_ribs.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "mesh/surface_distance.hpp"

namespace fibermold {

namespace {

/// m: a valley of the floor shallower than this is the meshed cavity's facets, not a rib.
constexpr double kLeastRibDepth = 1e-3;

/// The maximum (or minimum) of each cell's disk of radius r cells: a disk's dilation (erosion). A
/// disk, not a square, so that a slot's rib is found by its width whatever way the slot runs (a
/// square's reach across a diagonal slot is √2 times its side). The disk is its rows: row a of it
/// spans ±w(a) = ⌊√(r² − a²)⌋ cells, so each cell's value is the extreme over a of the extreme of
/// m's row i + a over ±w(a), and those row extremes grow by two cells from one w to the next: about
/// 3r + 1 comparisons a cell instead of the disk's πr².
Eigen::MatrixXd disk_filter(const Eigen::MatrixXd& m, Eigen::Index r, bool maximum, Progress* progress)
{
  const auto pick = [maximum](double a, double b) { return maximum ? std::max(a, b) : std::min(a, b); };
  const Eigen::Index rows = m.rows(), cols = m.cols();
  Eigen::MatrixXd out = m, row = m; // row: the extreme of m over ±w cells along each row
  for (Eigen::Index w = 0; w <= r; ++w) {
    if (progress && progress->interrupted()) throw Interrupted();
    if (w > 0)
      for (Eigen::Index j = 0; j < cols; ++j)
        for (Eigen::Index i = 0; i < rows; ++i) {
          if (j - w >= 0) row(i, j) = pick(row(i, j), m(i, j - w));
          if (j + w < cols) row(i, j) = pick(row(i, j), m(i, j + w));
        }
    // The disk's rows ±a whose half-width is w.
    for (Eigen::Index a = 0; a <= r; ++a) {
      if (static_cast<Eigen::Index>(std::floor(std::sqrt(double(r * r - a * a)))) != w) continue;
      for (Eigen::Index j = 0; j < cols; ++j)
        for (Eigen::Index i = 0; i < rows; ++i) {
          if (i + a < rows) out(i, j) = pick(out(i, j), row(i + a, j));
          if (i - a >= 0) out(i, j) = pick(out(i, j), row(i - a, j));
        }
    }
  }
  return out;
}

/// Cells from (i, j) to the nearest cell where `outside` holds (up to r + 1).
template <typename Outside> double inscribed_at(Eigen::Index i, Eigen::Index j, Eigen::Index r, const Outside& outside)
{
  double nearest = static_cast<double>(r + 1);
  for (Eigen::Index a = i - r; a <= i + r; ++a)
    for (Eigen::Index b = j - r; b <= j + r; ++b)
      if (outside(a, b)) nearest = std::min(nearest, std::hypot(double(a - i), double(b - j)));
  return nearest;
}

/// Cells from a rib's tip within which the valley it stands in is measured (valley_disk).
constexpr Eigen::Index kNearTip = 4;

/// The radius, in cells, of the largest disk of the valley of the floor that covers a cell within
/// kNearTip of a rib's tip (ti, tj): the valley the cells lower than `level` (just under the rib's root,
/// where the closing put the floor), a disk's radius its centre's distance to the nearest cell higher
/// than that (up to r + 1). The closing leaves cells that no disk of its size covers, where no rib is:
/// along the wall of a valley a cell or two wider than the disk, and in the corners of a wide one (a
/// notch's); a disk of the valley's width covers cells a few from there. A rib the closing filled is
/// covered by no disk wider than it near its tip, however low the ground a little farther off (a
/// narrow finger's slot, open to the plane around the finger).
double valley_disk(const Eigen::MatrixXd& floor, Eigen::Index ti, Eigen::Index tj, Eigen::Index r, double level)
{
  const auto wall = [&](Eigen::Index a, Eigen::Index b) {
    return a >= 0 && b >= 0 && a < floor.rows() && b < floor.cols() && floor(a, b) > level;
  };
  const Eigen::Index reach = kNearTip + r + 1; // the disks' centres
  Eigen::MatrixXd radius = Eigen::MatrixXd::Zero(2 * reach + 1, 2 * reach + 1);
  for (Eigen::Index a = -reach; a <= reach; ++a)
    for (Eigen::Index b = -reach; b <= reach; ++b)
      if (ti + a >= 0 && tj + b >= 0 && ti + a < floor.rows() && tj + b < floor.cols() && !wall(ti + a, tj + b))
        radius(a + reach, b + reach) = inscribed_at(ti + a, tj + b, r, wall);
  double widest = 0;
  for (Eigen::Index a = -reach; a <= reach; ++a)
    for (Eigen::Index b = -reach; b <= reach; ++b) {
      const double rho = radius(a + reach, b + reach);
      if (rho <= widest) continue;
      // Does the disk at (a, b) cover a cell within kNearTip of the tip: is it within rho of that disk?
      if (std::hypot(double(a), double(b)) <= rho + double(kNearTip)) widest = rho;
    }
  return widest;
}

/// The ribs of one half: `w` its pull (out of the cavity, away from the plane), the plane at height
/// `plane` along w.
std::vector<ThinRib> half_ribs(const SurfaceDistance& tree, const SurfaceMesh& cavity, const Eigen::Vector3d& w,
                               double plane, double cell, double thickness, double aspect, bool upper,
                               Progress* progress)
{
  const Eigen::Vector3d u = w.unitOrthogonal(), v = w.cross(u);
  const Eigen::VectorXd cu = cavity.vertices * u, cv = cavity.vertices * v, cw = cavity.vertices * w;
  const double margin = 2 * thickness, top = cw.maxCoeff() + cell; // the margin: wider than a rib
  const double u0 = cu.minCoeff() - margin, v0 = cv.minCoeff() - margin;
  const auto nu = static_cast<Eigen::Index>(std::ceil((cu.maxCoeff() + margin - u0) / cell));
  const auto nv = static_cast<Eigen::Index>(std::ceil((cv.maxCoeff() + margin - v0) / cell));
  const auto point = [&](Eigen::Index i, Eigen::Index j, double height) -> Eigen::Vector3d {
    return (u0 + (i + 0.5) * cell) * u + (v0 + (j + 0.5) * cell) * v + height * w;
  };
  // The half's floor: where each column, coming down along −w, meets the cavity; the plane below.
  Eigen::MatrixXd floor(nu, nv);
  for (Eigen::Index i = 0; i < nu; ++i) {
    if (progress && progress->interrupted()) throw Interrupted();
    for (Eigen::Index j = 0; j < nv; ++j) {
      const double hit = tree.ray_distance(point(i, j, top), -w);
      floor(i, j) = std::isfinite(hit) ? std::max(top - hit, plane) : plane;
    }
  }
  const auto r = static_cast<Eigen::Index>(std::floor(thickness / (2 * cell)));
  const Eigen::MatrixXd depth = disk_filter(disk_filter(floor, r, true, progress), r, false, progress) - floor;
  // The ribs: connected cells that stand deeper than the facets.
  const Eigen::MatrixX<bool> rib = depth.array() >= kLeastRibDepth;
  Eigen::MatrixXi seen = Eigen::MatrixXi::Zero(nu, nv);
  std::vector<ThinRib> out;
  for (Eigen::Index i0 = 0; i0 < nu; ++i0)
    for (Eigen::Index j0 = 0; j0 < nv; ++j0) {
      if (!rib(i0, j0) || seen(i0, j0)) continue;
      std::vector<std::pair<Eigen::Index, Eigen::Index>> cells{{i0, j0}};
      seen(i0, j0) = 1;
      for (std::size_t k = 0; k < cells.size(); ++k) {
        const auto [i, j] = cells[k];
        for (const auto& [di, dj] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
          const Eigen::Index a = i + di, b = j + dj;
          if (a < 0 || b < 0 || a >= nu || b >= nv || !rib(a, b) || seen(a, b)) continue;
          seen(a, b) = 1;
          cells.emplace_back(a, b);
        }
      }
      // Its thickness: the largest distance from a cell of it to the nearest cell outside it. Its tip: the
      // deepest cell (to a hundredth of a cell); of those the one farthest inside it, then the nearest its
      // middle (the cells' centroid: along a slot of even width, its middle rather than its end).
      const auto outside = [&](Eigen::Index a, Eigen::Index b) {
        return a < 0 || b < 0 || a >= nu || b >= nv || !rib(a, b);
      };
      Eigen::Vector2d middle = Eigen::Vector2d::Zero();
      for (const auto& [i, j] : cells) middle += Eigen::Vector2d(double(i), double(j)) / double(cells.size());
      const auto off = [&](Eigen::Index i, Eigen::Index j) {
        return (Eigen::Vector2d(double(i), double(j)) - middle).norm();
      };
      ThinRib best{upper, {}, 0, 0};
      Eigen::Index ti = i0, tj = j0;
      double inscribed = 0, tip = -1;
      for (const auto& [i, j] : cells) {
        const double nearest = inscribed_at(i, j, r, outside);
        inscribed = std::max(inscribed, nearest);
        const bool deeper = depth(i, j) > best.depth + 0.01 * cell, as_deep = depth(i, j) > best.depth - 0.01 * cell;
        if (deeper || (as_deep && (nearest > tip || (nearest == tip && off(i, j) < off(ti, tj))))) {
          best.depth = std::max(best.depth, depth(i, j));
          best.at = point(i, j, floor(i, j));
          ti = i, tj = j, tip = nearest;
        }
      }
      // A rib n cells across has its middle cell ⌈n/2⌉ cells from the nearer cell outside it.
      const double level = floor(ti, tj) + depth(ti, tj) - kLeastRibDepth;
      best.thickness = (2 * std::max(inscribed, valley_disk(floor, ti, tj, r, level)) - 0.5) * cell;
      if (best.thickness < thickness && best.depth > aspect * best.thickness) out.push_back(best);
    }
  return out;
}

} // namespace

std::vector<ThinRib> thin_ribs(const SurfaceMesh& cavity, const Parting& parting, double cell, Progress* progress,
                               double thickness, double aspect)
{
  const SurfaceDistance tree(cavity.vertices, cavity.faces);
  const Eigen::Vector3d pull = parting.normal.normalized();
  const double plane = pull.dot(parting.point);
  std::vector<ThinRib> ribs = half_ribs(tree, cavity, pull, plane, cell, thickness, aspect, true, progress);
  for (const ThinRib& r : half_ribs(tree, cavity, -pull, -plane, cell, thickness, aspect, false, progress))
    ribs.push_back(r);
  std::sort(ribs.begin(), ribs.end(), [](const ThinRib& a, const ThinRib& b) { return a.depth > b.depth; });
  return ribs;
}

} // namespace fibermold
