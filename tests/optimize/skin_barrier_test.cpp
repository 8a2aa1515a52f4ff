// The skin barrier between its samples: a route that passes under a notch's bottom, whose samples
// straddle the notch, is caught at the notch (optimize/skin_barrier.hpp).
#include <cmath>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "core/units.hpp"
#include "mesh/surface_distance.hpp"
#include "optimize/skin_barrier.hpp"

namespace fibermold {
namespace {

using units::mm;

/// A 60 × 16 × 16 mm bar (x from 0 to 60, y and z from −8 to 8) with a V-notch cut across its top
/// at x = 30: 2 mm wide at the top, its bottom a sharp edge at z = 2 mm. The cross-section in
/// (x, z), extruded along y.
SurfaceDistance notched_bar()
{
  const std::vector<Eigen::Vector2d> xz{{0, -8}, {60, -8}, {60, 8}, {31, 8}, {30, 2}, {29, 8}, {0, 8}};
  const int n = static_cast<int>(xz.size());
  Eigen::MatrixX3d v(2 * n, 3);
  for (int i = 0; i < n; ++i) {
    v.row(i) << xz[i].x() * mm, -8 * mm, xz[i].y() * mm;
    v.row(n + i) << xz[i].x() * mm, 8 * mm, xz[i].y() * mm;
  }
  std::vector<Eigen::Vector3i> f;
  // The caps, ear by ear (the polygon is not convex), and a quad per polygon edge.
  for (const auto& [a, b, c] : std::vector<std::array<int, 3>>{{0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {0, 4, 6}, {4, 5, 6}}) {
    f.emplace_back(a, c, b);
    f.emplace_back(n + a, n + b, n + c);
  }
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    f.emplace_back(i, j, n + j);
    f.emplace_back(i, n + j, n + i);
  }
  Eigen::MatrixX3i faces(static_cast<Eigen::Index>(f.size()), 3);
  for (std::size_t k = 0; k < f.size(); ++k) faces.row(static_cast<Eigen::Index>(k)) = f[k].transpose();
  // Outward: a positive enclosed volume.
  double volume = 0;
  for (Eigen::Index k = 0; k < faces.rows(); ++k)
    volume += v.row(faces(k, 0)).dot(v.row(faces(k, 1)).cross(v.row(faces(k, 2)))) / 6;
  if (volume < 0) faces.col(1).swap(faces.col(2));
  return SurfaceDistance(v, faces);
}

TEST(SkinBarrier, ARouteUnderANotchBetweenSamplesIsCaught)
{
  static const SurfaceDistance skin = notched_bar();
  // A straight route on the axis passes 2 mm under the notch's bottom. Samples every 4 mm sit at
  // x = 28 and 32 mm, 2.83 mm from it: at a skin distance of 2.5 mm they see nothing wrong.
  const HermiteSpline route({{0, 0, 0}, {60 * mm, 0, 0}});
  const SkinBarrier barrier(skin, 2.5 * mm, 1.5 * mm, route, 15);
  EXPECT_LT(barrier.value(route), HUGE_VAL);
  for (double x : {28.0, 32.0}) EXPECT_NEAR(skin.closest({x * mm, 0, 0}).distance / mm, std::sqrt(8.0), 1e-9);
  Eigen::Vector3d where;
  const double closest = barrier.closest_approach(route, where);
  EXPECT_NEAR(closest / mm, 2.0, 1e-3);
  EXPECT_NEAR(where.x() / mm, 30.0, 0.01);
  // 3 mm below the notch (5 mm from its bottom) the route clears it, and the bound says so
  // with its samples alone or a few probes between them.
  const HermiteSpline lower({{0, 0, -3 * mm}, {60 * mm, 0, -3 * mm}});
  EXPECT_GT(SkinBarrier(skin, 2.5 * mm, 1.5 * mm, lower, 15).closest_approach(lower, where) / mm, 4.99);
}

TEST(SkinBarrier, ItsValueAndGradientAreThoseOfAFreshBarrierWhereverTheRouteHasBeen)
{
  // value() and gradient() skip samples whose last distance, less how far they moved, is beyond the
  // band. A route walked up under the notch, sideways and back down, step by step, must see at each
  // step exactly what a barrier that has never seen it sees.
  static const SurfaceDistance skin = notched_bar();
  const HermiteSpline start({{0, 0, -4 * mm}, {30 * mm, 0, -4 * mm}, {60 * mm, 0, -4 * mm}});
  const SkinBarrier walked(skin, 2.5 * mm, 1.5 * mm, start, 30);
  int in_band = 0;
  for (int step = 0; step <= 40; ++step) {
    const double s = step / 40.0, rise = 7.5 * std::sin(M_PI * s) * mm, side = 5 * std::sin(2 * M_PI * s) * mm;
    const HermiteSpline route({{0, 0, -4 * mm}, {30 * mm, side, -4 * mm + rise}, {60 * mm, 0, -4 * mm}});
    const SkinBarrier fresh(skin, 2.5 * mm, 1.5 * mm, start, 30);
    const double value = fresh.value(route);
    EXPECT_EQ(walked.value(route), value) << "step " << step;
    const FiberParameterGradient g = walked.gradient(route), expected = fresh.gradient(route);
    for (std::size_t i = 0; i < g.points.size(); ++i) {
      EXPECT_EQ(g.points[i], expected.points[i]) << "step " << step;
      EXPECT_EQ(g.tangents[i], expected.tangents[i]) << "step " << step;
    }
    in_band += value > 0 && value < HUGE_VAL;
  }
  EXPECT_GT(in_band, 5); // the walk goes through the band, not only past it
}

TEST(SkinBarrier, ItsFeasibilityTestIsAFreshBarriersExactOneWhereverTheRouteHasBeen)
{
  // closest_approach(…, first_only) starts each sample from its last measurement less how far it
  // has moved. A route that jumps up into the notch and back down, by steps of up to 8 mm, must be
  // refused at exactly the steps a barrier that has never seen it finds a point within d_min, and
  // where it is refused the point found must be within d_min.
  static const SurfaceDistance skin = notched_bar();
  const HermiteSpline start({{0, 0, -4 * mm}, {30 * mm, 0, -4 * mm}, {60 * mm, 0, -4 * mm}});
  const SkinBarrier walked(skin, 2.5 * mm, 1.5 * mm, start, 12);
  int refused = 0, cleared = 0;
  for (int step = 0; step <= 60; ++step) {
    const double rise = 8.0 * std::fmod(0.618034 * step, 1.0) * mm;
    const HermiteSpline route({{0, 0, -4 * mm}, {30 * mm, 0.3 * mm, -4 * mm + rise}, {60 * mm, 0, -4 * mm}});
    const SkinBarrier fresh(skin, 2.5 * mm, 1.5 * mm, start, 12);
    Eigen::Vector3d where, fresh_where;
    const double exact = fresh.closest_approach(route, fresh_where);
    if (step % 3 == 0) (void)walked.value(route); // as the optimizer calls it, which measures some samples
    const double d = walked.closest_approach(route, where, true);
    EXPECT_EQ(d <= 2.5 * mm, exact <= 2.5 * mm) << "step " << step << ": exact " << exact / mm << " mm";
    if (d <= 2.5 * mm) {
      EXPECT_LE(skin.closest(where).distance, 2.5 * mm + 1e-9) << "step " << step;
    }
    (d <= 2.5 * mm ? refused : cleared) += 1;
  }
  EXPECT_GT(refused, 5);
  EXPECT_GT(cleared, 5);
  // Then by steps of 0.2 mm and without value(), samples 1 mm apart: the distances closest_approach
  // measured itself decide, and the bound's slack between samples (half their spacing) is small.
  const SkinBarrier dense(skin, 2.5 * mm, 1.5 * mm, start, 60);
  refused = cleared = 0;
  for (int step = 0; step <= 80; ++step) {
    const double rise = 8.0 * (1 - std::abs(step - 40) / 40.0) * mm;
    const HermiteSpline route({{0, 0, -4 * mm}, {30 * mm, 0.3 * mm, -4 * mm + rise}, {60 * mm, 0, -4 * mm}});
    Eigen::Vector3d where, fresh_where;
    const double exact = SkinBarrier(skin, 2.5 * mm, 1.5 * mm, start, 60).closest_approach(route, fresh_where);
    const double d = dense.closest_approach(route, where, true);
    EXPECT_EQ(d <= 2.5 * mm, exact <= 2.5 * mm) << "step " << step << ": exact " << exact / mm << " mm";
    (d <= 2.5 * mm ? refused : cleared) += 1;
  }
  EXPECT_GT(refused, 5);
  EXPECT_GT(cleared, 5);
}

} // namespace
} // namespace fibermold
