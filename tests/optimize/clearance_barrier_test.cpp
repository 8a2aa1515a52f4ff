// The barrier on the clearance between fibers, for optimizing again after collide.
#include <cmath>

#include <gtest/gtest.h>

#include "clearance_fixture.hpp"
#include "finite_differences.hpp"
#include "optimize/clearance_barrier.hpp"

namespace fibermold {
namespace {

using namespace test;

TEST(ClearanceBarrier, InfiniteAtTheClearanceZeroBeyondItsBandAndItsGradientMatchesDifferences)
{
  const Body body(mm(-30, -30, -15), mm(30, 30, 15));
  const auto routes_at = [](double gap) {
    return std::vector<Route>{route("a", {mm(-25, 0, -gap / 2), mm(0, 1, -gap / 2), mm(25, 0, -gap / 2)}),
                              route("b", {mm(2, -25, gap / 2), mm(0, 0, gap / 2 + 0.3), mm(-1, 25, gap / 2)})};
  };
  const FiberClearance measure(body.skin, routes_at(4.8), kRadius, kClearance, kSamplesPerLength);
  const ClearanceBarrier B(measure, routes_at(4.8), kClearance, kRadius);
  EXPECT_EQ(B.value(routes_at(3.5)), HUGE_VAL); // 0.5 mm of clearance
  EXPECT_EQ(B.value(routes_at(9.0)), 0.0);      // beyond the band
  std::vector<Route> r = routes_at(4.8);        // within the band
  const double v = B.value(r);
  ASSERT_GT(v, 0);
  ASSERT_TRUE(std::isfinite(v));
  const auto g = B.gradient(r);
  // Both fibers' points and tangents as one vector of variables.
  const auto variables = [](const std::vector<Route>& routes) {
    return test::stacked({routes[0].points, routes[0].tangents, routes[1].points, routes[1].tangents});
  };
  const test::ScalarFunction value = [&](const Eigen::VectorXd& v) {
    const auto lists = test::unstacked(v, {3, 3, 3, 3});
    std::vector<Route> moved = r;
    for (int f = 0; f < 2; ++f) moved[f].points = lists[2 * f], moved[f].tangents = lists[2 * f + 1];
    return B.value(moved);
  };
  const Eigen::VectorXd analytic = test::stacked({g[0].points, g[0].tangents, g[1].points, g[1].tangents});
  ASSERT_EQ(analytic.size(), 36);
  // The barrier's measure is the distance between sampled centre lines: 1e-4 of the largest entry.
  EXPECT_TRUE(test::matches_fd(analytic, test::fd_gradient(value, variables(r), 1e-7), 1e-4, 1e-3));
  EXPECT_GT(analytic.cwiseAbs().maxCoeff(), 100); // per m: the barrier pushes
}

} // namespace
} // namespace fibermold
