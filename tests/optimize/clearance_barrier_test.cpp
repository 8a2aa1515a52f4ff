// The barrier on the clearance between fibers, for optimizing again after collide.
#include <cmath>

#include <gtest/gtest.h>

#include "clearance_fixture.hpp"
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
  EXPECT_GT(largest, 100); // per m: the barrier pushes
}

} // namespace
} // namespace fibermold
