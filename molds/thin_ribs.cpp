#include "molds/thin_ribs.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "mesh/surface_distance.hpp"

namespace fibermold {

namespace {

/// m: a valley of the floor shallower than this is the meshed cavity's facets, not a rib.
constexpr double kLeastRibDepth = 1e-3;

/// The running maximum (or minimum) of each row and column over a window of 2r + 1 cells: a
/// square's dilation (erosion).
Eigen::MatrixXd square_filter(const Eigen::MatrixXd& m, Eigen::Index r, bool maximum)
{
  const auto pass = [&](const Eigen::MatrixXd& in) {
    Eigen::MatrixXd out = in;
    for (Eigen::Index i = 0; i < in.rows(); ++i)
      for (Eigen::Index j = 0; j < in.cols(); ++j) {
        const Eigen::Index a = std::max<Eigen::Index>(0, i - r), b = std::min<Eigen::Index>(in.rows() - 1, i + r);
        const auto window = in.col(j).segment(a, b - a + 1);
        out(i, j) = maximum ? window.maxCoeff() : window.minCoeff();
      }
    return out;
  };
  return pass(pass(m).transpose()).transpose();
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
  const Eigen::MatrixXd depth = square_filter(square_filter(floor, r, true), r, false) - floor;
  // The ribs: connected cells that stand deeper than the facets; each one's thickness from the
  // largest distance of its cells to the nearest cell outside it.
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
      ThinRib best{upper, {}, 0, 0};
      double inscribed = 0, tip = 0; // cells: the largest distance from a rib cell to the nearest cell outside it
      for (const auto& [i, j] : cells) {
        double nearest = static_cast<double>(r + 1);
        for (Eigen::Index a = std::max<Eigen::Index>(0, i - r); a <= std::min(nu - 1, i + r); ++a)
          for (Eigen::Index b = std::max<Eigen::Index>(0, j - r); b <= std::min(nv - 1, j + r); ++b)
            if (!rib(a, b)) nearest = std::min(nearest, std::hypot(double(a - i), double(b - j)));
        inscribed = std::max(inscribed, nearest);
        // The tip: the deepest cell (to a hundredth of a cell), the one in the rib's middle of those.
        const bool deeper = depth(i, j) > best.depth + 0.01 * cell;
        if (deeper || (depth(i, j) > best.depth - 0.01 * cell && nearest > tip)) {
          best.depth = std::max(best.depth, depth(i, j));
          best.at = point(i, j, floor(i, j));
          tip = nearest;
        }
      }
      // A rib n cells across has its middle cell ⌈n/2⌉ cells from the nearer cell outside it.
      best.thickness = (2 * inscribed - 0.5) * cell;
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
