// The clearance measure of the collide stage: segment closest points, pairs and skin.
#include <cmath>

#include <gtest/gtest.h>

#include "clearance_fixture.hpp"
#include "optimize/collision_resolution.hpp"
#include "optimize/fiber_clearance.hpp"

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

} // namespace
} // namespace fibermold
