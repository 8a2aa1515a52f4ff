// The resolution of collisions (collide stage): the cases the issue names, on boxes.
#include <cmath>

#include <gtest/gtest.h>

#include "clearance_fixture.hpp"
#include "optimize/collision_resolution.hpp"

namespace fibermold {
namespace {

using namespace test;

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
  EXPECT_EQ(r.collided.size(), 3u); // every pair
  EXPECT_LT(r.before / units::mm, -1.0);
  EXPECT_GE(smallest(measure, r.routes) / units::mm, 1.0 - 1e-3); // pairs and skin
  for (int f = 0; f < 3; ++f) {
    EXPECT_EQ(r.routes[f].points.front(), routes[f].points.front());
    EXPECT_EQ(r.routes[f].points.back(), routes[f].points.back());
  }
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
  EXPECT_NEAR(smallest(measure, routes) / units::mm, 5 - 1.5, 1e-6); // the ends, 5 mm from the skin
  ResolutionSettings with_room = settings();
  with_room.room = 5 * units::mm; // room is only where fibers move: a clear routing stays put
  EXPECT_FALSE(resolve_collisions(measure, routes, with_room).changed);
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
    EXPECT_NE(std::string(e.what()).find("fibers a and b have fixed end points 0.00 mm apart"), std::string::npos)
        << e.what();
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
    const std::string what = e.what();
    EXPECT_TRUE(what.rfind("fibers a and b", 0) == 0 || what.rfind("fiber a and the skin", 0) == 0 ||
                what.rfind("fiber b and the skin", 0) == 0)
        << what;
  }
}

} // namespace
} // namespace fibermold
