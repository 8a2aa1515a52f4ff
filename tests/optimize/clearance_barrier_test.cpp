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

TEST(ClearanceBarrier, AFibersOwnPairsHoldAllOfTheGradientThatChangesWhenItAloneMoves)
{
  // Three fibers, each within the band of the other two: the gradient of the pairs that include a
  // fiber (what the optimizer's model differentiates when that fiber alone moves) is the whole
  // gradient less the third pair's, so the three restricted gradients sum to twice the whole. A
  // fourth fiber far from the others has no pair in the band: its restricted gradient is zero.
  const Body body(mm(-30, -30, -15), mm(30, 30, 15));
  const std::vector<Route> r{route("a", {mm(-25, 0, -2.4), mm(0, 1, -2.4), mm(25, 0, -2.4)}),
                             route("b", {mm(2, -25, 2.4), mm(0, 0, 2.7), mm(-1, 25, 2.4)}),
                             route("c", {mm(-25, 5.8, -2.4), mm(0, 5.8, -2.4), mm(25, 5.8, -2.4)}),
                             route("d", {mm(-25, -20, 12), mm(0, -20, 12), mm(25, -20, 12)})};
  const FiberClearance measure(body.skin, r, kRadius, kClearance, kSamplesPerLength);
  const ClearanceBarrier B(measure, r, kClearance, kRadius);
  ASSERT_TRUE(std::isfinite(B.value(r)));
  const auto flat = [](const std::vector<FiberParameterGradient>& g) {
    std::vector<std::vector<Eigen::Vector3d>> lists;
    for (const FiberParameterGradient& each : g) {
      lists.push_back(each.points);
      lists.push_back(each.tangents);
    }
    return test::stacked(lists);
  };
  const Eigen::VectorXd whole = flat(B.gradient(r));
  const Eigen::VectorXd sum = flat(B.gradient(r, 0)) + flat(B.gradient(r, 1)) + flat(B.gradient(r, 2));
  ASSERT_GT(whole.cwiseAbs().maxCoeff(), 100); // every pair within the band: the barrier pushes
  EXPECT_LE((sum - 2 * whole).cwiseAbs().maxCoeff(), 1e-12 * whole.cwiseAbs().maxCoeff());
  // a's pairs are the whole less the b-c pair's, measured on its own by a barrier of b and c alone.
  const std::vector<Route> bc{r[1], r[2]};
  const FiberClearance measure_bc(body.skin, bc, kRadius, kClearance, kSamplesPerLength);
  const ClearanceBarrier B_bc(measure_bc, bc, kClearance, kRadius);
  std::vector<FiberParameterGradient> pair_bc = B.gradient(r, 3); // zeros in every fiber's shape
  const std::vector<FiberParameterGradient> g_bc = B_bc.gradient(bc);
  pair_bc[1] = g_bc[0];
  pair_bc[2] = g_bc[1];
  ASSERT_GT(flat(pair_bc).cwiseAbs().maxCoeff(), 100);
  EXPECT_LE((flat(B.gradient(r, 0)) - (whole - flat(pair_bc))).cwiseAbs().maxCoeff(),
            1e-12 * whole.cwiseAbs().maxCoeff());
  EXPECT_EQ(flat(B.gradient(r, 3)).cwiseAbs().maxCoeff(), 0.0);
}

} // namespace
} // namespace fibermold
