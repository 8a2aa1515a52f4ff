// The clearance measure and the resolution of collisions (collide stage): the cases the issue
// names, on boxes. Muscles 3 mm across, 1 mm clearance: centre lines at least 4 mm apart and
// 2.5 mm inside the skin.

#include <cmath>

#include <gtest/gtest.h>

#include "core/units.hpp"
#include "optimize/clearance_barrier.hpp"
#include "optimize/collision_resolution.hpp"
#include "../primitives.hpp"

namespace fibermold {
namespace {

constexpr double kRadius = 1.5e-3, kClearance = 1e-3, kSamplesPerLength = 4000;

Eigen::Vector3d mm(double x, double y, double z) { return Eigen::Vector3d(x, y, z) * units::mm; }

Route route(std::string name, const std::vector<Eigen::Vector3d>& points)
{
  const HermiteSpline s(points);
  return {std::move(name), s.points(), s.tangents()};
}

struct Body {
  SurfaceMesh surface;
  SurfaceDistance skin;
  Body(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi)
      : surface(test::box(lo, hi, 4)), skin(surface.vertices, surface.faces)
  {
  }
};

ResolutionSettings settings()
{
  ResolutionSettings s;
  s.clearance = kClearance;
  return s;
}

double smallest(const FiberClearance& measure, const std::vector<Route>& routes)
{
  return smallest_clearance(measure.contacts(routes, 10 * units::mm));
}

TEST(FiberClearance, SegmentClosestPoints)
{
  double s, t;
  closest_points_of_segments({0, 0, 0}, {2, 0, 0}, {1, -1, 1}, {1, 1, 1}, s, t);  // crossing at right angles
  EXPECT_NEAR(s, 0.5, 1e-12);
  EXPECT_NEAR(t, 0.5, 1e-12);
  closest_points_of_segments({0, 0, 0}, {1, 0, 0}, {3, 1, 0}, {5, 1, 0}, s, t);  // collinear-ish, apart: end to end
  EXPECT_NEAR(s, 1, 1e-12);
  EXPECT_NEAR(t, 0, 1e-12);
  closest_points_of_segments({0, 0, 0}, {1, 0, 0}, {0.25, 2, 0}, {0.75, 2, 0}, s, t);  // parallel, overlapping
  EXPECT_NEAR((Eigen::Vector3d(s, 0, 0) - Eigen::Vector3d(0.25 + 0.5 * t, 2, 0)).norm(), 2, 1e-12);
}

TEST(FiberClearance, MeasuresPairsAndSkin)
{
  const Body body(mm(-30, -30, -15), mm(30, 30, 15));
  const std::vector<Route> routes{route("a", {mm(-25, 0, -1), mm(0, 0, -1), mm(25, 0, -1)}),
                                  route("b", {mm(0, -25, 2), mm(0, 0, 2), mm(0, 25, 2)}),
                                  route("c", {mm(-20, 10, 11), mm(20, 10, 11)})};
  const FiberClearance measure(body.skin, routes, kRadius, kClearance, kSamplesPerLength);
  const std::vector<Contact> worst = worst_per_pair(measure.contacts(routes, 3 * units::mm));
  ASSERT_EQ(worst.size(), 2u);
  EXPECT_EQ(worst[0].a, 0);  // a and b: 3 mm between centre lines, 0 mm between the muscles
  EXPECT_EQ(worst[0].b, 1);
  EXPECT_NEAR(worst[0].clearance / units::mm, 0.0, 1e-9);
  EXPECT_NEAR(worst[0].normal.z(), -1.0, 1e-9);
  EXPECT_EQ(worst[1].a, 2);  // c runs 4 mm under the top: 2.5 mm of clearance
  EXPECT_EQ(worst[1].b, -1);
  EXPECT_NEAR(worst[1].clearance / units::mm, 2.5, 1e-9);
  EXPECT_NEAR(worst[1].normal.z(), -1.0, 1e-9);
}

TEST(CollisionResolution, CrossingFibersMoveApartSymmetricallyByTheLeastAmount)
{
  const Body body(mm(-30, -30, -15), mm(30, 30, 15));
  const std::vector<Route> routes{route("a", {mm(-25, 0, -0.2), mm(0, 0, -0.2), mm(25, 0, -0.2)}),
                                  route("b", {mm(0, -25, 0.2), mm(0, 0, 0.2), mm(0, 25, 0.2)})};
  const FiberClearance measure(body.skin, routes, kRadius, kClearance, kSamplesPerLength);
  const CollisionResolution r = resolve_collisions(measure, routes, settings());
  EXPECT_TRUE(r.changed);
  ASSERT_EQ(r.collided.size(), 1u);
  EXPECT_NEAR(r.before / units::mm, 0.4 - 3, 1e-6);
  EXPECT_NEAR(r.after / units::mm, 1.0, 0.05);
  EXPECT_NEAR(smallest(measure, r.routes) / units::mm, 1.0, 0.05);
  // The crossing points must end 4 mm apart: 3.6 mm of movement, half each, straight apart.
  const Eigen::Vector3d move_a = (r.routes[0].points[1] - routes[0].points[1]) / units::mm;
  const Eigen::Vector3d move_b = (r.routes[1].points[1] - routes[1].points[1]) / units::mm;
  EXPECT_NEAR(move_a.z(), -1.8, 0.05);
  EXPECT_NEAR(move_b.z(), 1.8, 0.05);
  EXPECT_NEAR(move_a.norm(), move_b.norm(), 0.01);
  EXPECT_NEAR(move_a.norm() + move_b.norm(), 3.6, 0.05);
  for (int f = 0; f < 2; ++f) {
    EXPECT_EQ(r.routes[f].points.front(), routes[f].points.front());
    EXPECT_EQ(r.routes[f].points.back(), routes[f].points.back());
  }
}

TEST(CollisionResolution, ThreeTwistedFibersAreSeparated)
{
  const Body body(mm(-50, -15, -15), mm(50, 15, 15));
  std::vector<Route> routes;
  for (int i = 0; i < 3; ++i) {
    std::vector<Eigen::Vector3d> points;
    for (double x : {-40.0, -20.0, 0.0, 20.0, 40.0}) {
      const double radius = 0.8 + 3.2 * std::abs(x) / 40, angle = 2 * M_PI * (x / 80 + i / 3.0);
      points.push_back(mm(x, radius * std::cos(angle), radius * std::sin(angle)));
    }
    routes.push_back(route(std::string(1, static_cast<char>('a' + i)), points));
  }
  const FiberClearance measure(body.skin, routes, kRadius, kClearance, kSamplesPerLength);
  const CollisionResolution r = resolve_collisions(measure, routes, settings());
  EXPECT_EQ(r.collided.size(), 3u);  // every pair
  EXPECT_LT(r.before / units::mm, -1.0);
  EXPECT_GE(smallest(measure, r.routes) / units::mm, 1.0 - 1e-3);
  for (int f = 0; f < 3; ++f) EXPECT_EQ(r.routes[f].points.back(), routes[f].points.back());
}

TEST(CollisionResolution, FiberGrazingTheSkinIsPushedInside)
{
  const Body body(mm(-30, -10, -10), mm(30, 10, 10));
  const std::vector<Route> routes{route("a", {mm(-25, 0, 0), mm(0, 0, 8), mm(25, 0, 0)})};
  const FiberClearance measure(body.skin, routes, kRadius, kClearance, kSamplesPerLength);
  const CollisionResolution r = resolve_collisions(measure, routes, settings());
  ASSERT_EQ(r.collided.size(), 1u);
  EXPECT_EQ(r.collided[0].b, -1);
  EXPECT_NEAR(r.before / units::mm, 0.5, 0.01);
  EXPECT_NEAR(smallest(measure, r.routes) / units::mm, 1.0, 0.05);
  EXPECT_NEAR(r.routes[0].points[1].z() / units::mm, 7.5, 0.05);
}

TEST(CollisionResolution, ClearRoutingIsLeftUnchanged)
{
  const Body body(mm(-30, -30, -15), mm(30, 30, 15));
  const std::vector<Route> routes{route("a", {mm(-25, -5, 0), mm(0, -4, 1), mm(25, -5, 0)}),
                                  route("b", {mm(-25, 5, 0), mm(0, 4, -1), mm(25, 5, 0)})};
  const FiberClearance measure(body.skin, routes, kRadius, kClearance, kSamplesPerLength);
  const CollisionResolution r = resolve_collisions(measure, routes, settings());
  EXPECT_FALSE(r.changed);
  EXPECT_TRUE(r.collided.empty());
  EXPECT_GT(r.before / units::mm, 1.0);
  for (int f = 0; f < 2; ++f) {
    EXPECT_EQ(r.routes[f].points, routes[f].points);
    EXPECT_EQ(r.routes[f].tangents, routes[f].tangents);
  }
}

TEST(CollisionResolution, SharedEndPointIsImpossible)
{
  const Body body(mm(-30, -30, -15), mm(30, 30, 15));
  const std::vector<Route> routes{route("a", {mm(-25, 0, 0), mm(0, -5, 0), mm(25, -8, 0)}),
                                  route("b", {mm(-25, 0, 0), mm(0, 5, 0), mm(25, 8, 0)})};
  const FiberClearance measure(body.skin, routes, kRadius, kClearance, kSamplesPerLength);
  try {
    resolve_collisions(measure, routes, settings());
    FAIL() << "a shared end point cannot be cleared";
  } catch (const CollisionError& e) {
    EXPECT_NE(std::string(e.what()).find("fibers a and b have fixed end points 0.00 mm apart"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("(-25.00, 0.00, 0.00) mm"), std::string::npos) << e.what();
  }
}

TEST(CollisionResolution, PassageNarrowerThanTwoMusclesIsImpossible)
{
  // A 7 mm square bar: each centre line must stay within 1 mm of the axis, the two 4 mm apart.
  const Body body(mm(-30, -3.5, -3.5), mm(30, 3.5, 3.5));
  const std::vector<Route> routes{route("a", {mm(-30, -1.5, -1.5), mm(0, -0.5, -0.5), mm(30, -1.5, -1.5)}),
                                  route("b", {mm(-30, 1.5, 1.5), mm(0, 0.5, 0.5), mm(30, 1.5, 1.5)})};
  const FiberClearance measure(body.skin, routes, kRadius, kClearance, kSamplesPerLength);
  try {
    resolve_collisions(measure, routes, settings());
    FAIL() << "two muscles do not fit through";
  } catch (const CollisionError& e) {
    EXPECT_NE(std::string(e.what()).find("cannot be given 1.00 mm of clearance near ("), std::string::npos) << e.what();
  }
}

TEST(ClearanceBarrier, InfiniteAtTheClearanceZeroBeyondItsBandAndItsGradientMatchesDifferences)
{
  const Body body(mm(-30, -30, -15), mm(30, 30, 15));
  const auto routes_at = [](double gap) {
    return std::vector<Route>{route("a", {mm(-25, 0, -gap / 2), mm(0, 1, -gap / 2), mm(25, 0, -gap / 2)}),
                              route("b", {mm(2, -25, gap / 2), mm(0, 0, gap / 2 + 0.3), mm(-1, 25, gap / 2)})};
  };
  const FiberClearance measure(body.skin, routes_at(4.8), kRadius, kClearance, kSamplesPerLength);
  const ClearanceBarrier B(measure, kClearance, kRadius);
  EXPECT_EQ(B.value(routes_at(3.5)), HUGE_VAL);  // 0.5 mm of clearance
  EXPECT_EQ(B.value(routes_at(9.0)), 0.0);       // beyond the band
  std::vector<Route> r = routes_at(4.8);         // within the band
  const double v = B.value(r);
  ASSERT_GT(v, 0);
  ASSERT_TRUE(std::isfinite(v));
  const auto g = B.gradient(r);
  int checked = 0;
  double largest = 0;
  for (int f = 0; f < 2; ++f)
    for (int k = 0; k < 3; ++k)
      for (int kind = 0; kind < 2; ++kind)
        for (int c = 0; c < 3; ++c) {
          const double h = 1e-7;
          std::vector<Route> plus = r, minus = r;
          (kind ? plus[f].tangents : plus[f].points)[k][c] += h;
          (kind ? minus[f].tangents : minus[f].points)[k][c] -= h;
          const double fd = (B.value(plus) - B.value(minus)) / (2 * h);
          const double analytic = (kind ? g[f].tangents : g[f].points)[k][c];
          EXPECT_NEAR(analytic, fd, 1e-4 * std::abs(fd) + 1e-3) << "fiber " << f << " point " << k << " kind " << kind;
          largest = std::max(largest, std::abs(analytic));
          ++checked;
        }
  EXPECT_EQ(checked, 36);
  EXPECT_GT(largest, 100);  // per m: the barrier pushes
}

} // namespace
} // namespace fibermold
