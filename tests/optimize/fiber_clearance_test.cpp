// The clearance measure of the collide stage: segment closest points, pairs and skin.
#include <cmath>

#include <gtest/gtest.h>

#include "clearance_fixture.hpp"
#include "optimize/collision_resolution.hpp"
#include "optimize/fiber_clearance.hpp"
#include "optimize/skin_barrier.hpp"

namespace fibermold {
namespace {

using namespace test;

TEST(FiberClearance, SegmentClosestPoints)
{
  double s, t;
  closest_points_of_segments({0, 0, 0}, {2, 0, 0}, {1, -1, 1}, {1, 1, 1}, s, t); // crossing at right angles
  EXPECT_NEAR(s, 0.5, 1e-12);
  EXPECT_NEAR(t, 0.5, 1e-12);
  closest_points_of_segments({0, 0, 0}, {1, 0, 0}, {3, 1, 0}, {5, 1, 0}, s, t); // collinear-ish, apart: end to end
  EXPECT_NEAR(s, 1, 1e-12);
  EXPECT_NEAR(t, 0, 1e-12);
  closest_points_of_segments({0, 0, 0}, {1, 0, 0}, {0.25, 2, 0}, {0.75, 2, 0}, s, t); // parallel, overlapping
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
  EXPECT_EQ(worst[0].a, 0); // a and b: 3 mm between centre lines, 0 mm between the muscles
  EXPECT_EQ(worst[0].b, 1);
  EXPECT_NEAR(worst[0].clearance / units::mm, 0.0, 1e-9);
  EXPECT_NEAR(worst[0].normal.z(), -1.0, 1e-9);
  EXPECT_EQ(worst[1].a, 2); // c runs 4 mm under the top: 2.5 mm of clearance
  EXPECT_EQ(worst[1].b, -1);
  EXPECT_NEAR(worst[1].clearance / units::mm, 2.5, 1e-9);
  EXPECT_NEAR(worst[1].normal.z(), -1.0, 1e-9);
}

/// Collide tests the skin where the optimizer's skin barrier held it: the barrier leaves out 8 mm
/// of arc (2 (2 radius + clearance)) at an end on the skin, measured along the route it started
/// from, and a route that has moved since covers that arc in fewer or more parameters.
TEST(FiberClearance, TestsTheSkinWhereTheSkinBarrierHeldIt)
{
  const auto spline_of = [](const Route& r) { return HermiteSpline(r.points, r.tangents); };
  const Body body(mm(-30, -30, -15), mm(30, 30, 15));
  // The start creeps along the bottom in 1 mm spans: its first 8 mm of arc end in the fourth span.
  const Route start =
      route("a", {mm(-30, 0, -12.8), mm(-29, 0, -12.8), mm(-28, 0, -12.8), mm(-27, 0, -12.8), mm(30, 0, 0)});
  // Optimized, its first span is 10 mm long, 2.2 mm over the bottom, then it rises to the axis.
  const Route moved = route("a", {mm(-30, 0, -12.8), mm(-20, 0, -12.8), mm(-10, 0, 0), mm(0, 0, 0), mm(30, 0, 0)});
  const SkinBarrier barrier(body.skin, kRadius + kClearance, kRadius, spline_of(start), 200);
  Eigen::Vector3d where;
  EXPECT_GT(barrier.closest_approach(spline_of(moved), where) / units::mm, 2.5); // where it holds, the route is clear
  const std::vector<Route> routes{moved};
  const FiberClearance held(body.skin, routes, kRadius, kClearance, kSamplesPerLength, 0, {barrier.held()});
  EXPECT_TRUE(held.contacts(held.lines(routes), 0.999 * kClearance).empty());
  // Measured along the moved route instead, the 8 mm end in its first span: the stretch about
  // 2.2 mm over the bottom (0.7 mm of clearance, less where the spline swings under it) is tested,
  // which the barrier never held (collide then failed with "optimizing again left a fiber and the
  // skin closer than the clearance").
  const FiberClearance own(body.skin, routes, kRadius, kClearance, kSamplesPerLength);
  const std::vector<Contact> found = own.contacts(own.lines(routes), 0.999 * kClearance);
  ASSERT_FALSE(found.empty());
  EXPECT_TRUE(found.front().with_skin());
  EXPECT_LT(smallest_clearance(found) / units::mm, 0.71);
  // Where the barrier holds it, both see the skin: the same route low to the end.
  const std::vector<Route> low{
      route("a", {mm(-30, 0, -12.8), mm(-20, 0, -12.8), mm(-10, 0, -12.8), mm(0, 0, -12.8), mm(30, 0, -12.8)})};
  EXPECT_LT(barrier.closest_approach(spline_of(low.front()), where) / units::mm, 2.21);
  const FiberClearance held_low(body.skin, low, kRadius, kClearance, kSamplesPerLength, 0, {barrier.held()});
  const std::vector<Contact> seen = held_low.contacts(held_low.lines(low), 0.999 * kClearance);
  ASSERT_FALSE(seen.empty());
  EXPECT_NEAR(smallest_clearance(seen) / units::mm, 0.7, 0.01);
}

} // namespace
} // namespace fibermold
