#include <cmath>

#include <gtest/gtest.h>

#include "finite_differences.hpp"
#include "optimize/barrier.hpp"
#include "optimize/bend_radius.hpp"
#include "optimize/fiber_curvature.hpp"

namespace fibermold {
namespace {

TEST(Barrier, DerivativesAndSupport)
{
  const double dhat = 0.1;
  EXPECT_EQ(barrier(0.1, dhat), 0);
  EXPECT_EQ(barrier(0.5, dhat), 0);
  EXPECT_EQ(barrier(0, dhat), HUGE_VAL);
  EXPECT_GT(barrier(1e-6, dhat), barrier(1e-3, dhat));
  int checked = 0;
  for (double d : {1e-4, 0.003, 0.03, 0.07, 0.0999}) {
    const Eigen::VectorXd x = Eigen::VectorXd::Constant(1, d), one = Eigen::VectorXd::Ones(1);
    const test::ScalarFunction b = [&](const Eigen::VectorXd& y) { return barrier(y[0], dhat); };
    const test::ScalarFunction db = [&](const Eigen::VectorXd& y) { return barrier_gradient(y[0], dhat); };
    EXPECT_TRUE(test::matches_fd(barrier_gradient(d, dhat), test::central_difference(b, x, one, 1e-8 * d),
                                 test::kFdTolerance, 1e-12))
        << d;
    EXPECT_TRUE(test::matches_fd(barrier_hessian(d, dhat), test::central_difference(db, x, one, 1e-8 * d),
                                 test::kFdTolerance, 1e-9))
        << d;
    ++checked;
  }
  EXPECT_EQ(checked, 5);
  const PressureBarrier pb{425e3, 20e3};
  EXPECT_EQ(pb.value(200e3), 0);
  EXPECT_GT(pb.value(1e3), 0);
  EXPECT_GT(pb.value(424e3), 0);
  EXPECT_LT(pb.gradient(1e3), 0);   // pushes up from 0
  EXPECT_GT(pb.gradient(424e3), 0); // and down from p_max
  EXPECT_EQ(pb.value(-1), HUGE_VAL);
}

TEST(FiberCurvature, CircleAndStraightLineAndGradient)
{
  // A straight fiber has no curvature.
  EXPECT_NEAR(fiber_curvature(HermiteSpline({{0, 0, 0}, {0.05, 0, 0}, {0.1, 0, 0}})), 0, 1e-12);
  // A quarter circle of radius r: ∫ κ² ds = (1/r²)(π r / 2) = π / (2 r), within the cubic's accuracy.
  const double r = 0.02, a = r * M_PI / 4;
  const HermiteSpline arc(
      {{r, 0, 0}, {r / std::sqrt(2.0), r / std::sqrt(2.0), 0}, {0, r, 0}},
      {Eigen::Vector3d(0, a, 0), Eigen::Vector3d(-a, a, 0) / std::sqrt(2.0), Eigen::Vector3d(-a, 0, 0)});
  EXPECT_NEAR(fiber_curvature(arc), M_PI / (2 * r), 0.02 * M_PI / (2 * r));

  const std::vector<Eigen::Vector3d> P{{0, 0, 0}, {0.03, 0.01, 0.002}, {0.06, -0.005, 0.01}, {0.1, 0, 0}};
  const HermiteSpline s(P);
  const std::vector<Eigen::Vector3d> T = s.tangents();
  const FiberParameterGradient g = fiber_curvature_gradient(s);
  const test::ScalarFunction curvature = [&](const Eigen::VectorXd& v) {
    const auto lists = test::unstacked(v, {P.size(), T.size()});
    return fiber_curvature(HermiteSpline(lists[0], lists[1]));
  };
  ASSERT_GT(test::stacked({g.points, g.tangents}).cwiseAbs().maxCoeff(), 0);
  EXPECT_TRUE(test::matches_fd(test::stacked({g.points, g.tangents}),
                               test::fd_gradient(curvature, test::stacked({P, T}), 1e-8)));
}

/// A quarter circle of radius r in the xy-plane, as a two-span Hermite spline.
HermiteSpline quarter_circle(double r)
{
  const double a = r * M_PI / 4;
  return HermiteSpline(
      {{r, 0, 0}, {r / std::sqrt(2.0), r / std::sqrt(2.0), 0}, {0, r, 0}},
      {Eigen::Vector3d(0, a, 0), Eigen::Vector3d(-a, a, 0) / std::sqrt(2.0), Eigen::Vector3d(-a, 0, 0)});
}

TEST(BendRadius, SmallestBendOfACircleAndALineAndWhere)
{
  // The cubic Hermite quarter circle bends within 5 % of its radius everywhere (its tightest:
  // 19.08 mm), as a scan 100x denser finds too.
  const SmallestBend arc = smallest_bend(quarter_circle(0.02));
  EXPECT_NEAR(arc.radius, 0.02, 0.05 * 0.02);
  EXPECT_NEAR(arc.radius, smallest_bend(quarter_circle(0.02), 6400).radius, 1e-9);
  EXPECT_NEAR(arc.where.norm(), 0.02, 2e-4);
  EXPECT_EQ(smallest_bend(HermiteSpline({{0, 0, 0}, {0.05, 0, 0}, {0.1, 0, 0}})).radius, HUGE_VAL);

  // A straight 100 mm route with one control point pulled 8 mm sideways: the tightest bend is at
  // that point (x = 50 mm); the scan's refinement finds the same radius as a 20x denser scan.
  const HermiteSpline kink({{0, 0, 0}, {0.025, 0, 0}, {0.05, 0.008, 0}, {0.075, 0, 0}, {0.1, 0, 0}});
  const SmallestBend coarse = smallest_bend(kink, 8), fine = smallest_bend(kink, 2000);
  EXPECT_NEAR(coarse.radius, fine.radius, 1e-6 * fine.radius);
  EXPECT_NEAR(coarse.where.x(), 0.05, 1e-3);
  EXPECT_NEAR(coarse.arc_length, 0.05 + 0.0013, 0.002); // half the length, a little more for the bump
  EXPECT_NEAR(1 / curvature(kink, coarse.t), coarse.radius, 1e-12);
}

TEST(BendRadius, TheTighterOfTwoNearlyEqualBendsIsFoundWhereverTheScanFallsOnThem)
{
  // One span with a bend inside it (u ≈ 0.33) and one at its end (u = 1) of nearly equal radius.
  // As the end's tangent turns (by 10 µm over the sweep), the tighter bend passes from the inner
  // one to the end. The end is a scan point, the inner bend's peak is not (the 64-point scan sees
  // it 2.8e-4 low): refining only the scan's highest point found the end for turns where the inner
  // bend was still the tighter, and the bend barrier jumped there. The tightest found is the one a
  // scan 300× denser finds, on both sides of the swap.
  int swaps = 0;
  double first_where = -1;
  for (int i = 0; i <= 200; ++i) {
    const double turn = -0.01137 + 1e-5 * i / 200;
    const HermiteSpline s({{0, 0, 0}, {0.05, 0, 0}},
                          {Eigen::Vector3d(0.065, 0.05, 0), Eigen::Vector3d(0.035, turn, 0.002)});
    const SmallestBend found = smallest_bend(s, BendBarrier::kTightestScan), dense = smallest_bend(s, 20000);
    ASSERT_NEAR(found.radius, dense.radius, 1e-9 * dense.radius) << "turn " << turn;
    if (first_where < 0) first_where = found.t;
    swaps += std::abs(found.t - first_where) > 0.25;
  }
  EXPECT_GT(swaps, 0); // the sweep does cross from one bend to the other
}

TEST(BendRadius, BarrierIsSmoothWhereTwoNearlyEqualBendsSwap)
{
  // The span of the test above, its two bends in the barrier's band: as the end's tangent turns
  // through the swap, the barrier's gradient turns smoothly. A sample at the tighter bend alone
  // (the barrier then a max over the two) made it jump from one bend's gradient to the other's, a
  // kink a smooth model keeps predicting a decrease across. Each step (5e-8 of turn) changes the
  // gradient by 2.2e-4 of itself; the sample at the tighter bend alone changed it by 1.7e-4 to
  // 2.5e-4, and by 0.30 at the swap.
  const auto spline = [](double turn) {
    return HermiteSpline({{0, 0, 0}, {0.05, 0, 0}},
                         {Eigen::Vector3d(0.065, 0.05, 0), Eigen::Vector3d(0.035, turn, 0.002)});
  };
  const double R = 0.97 * smallest_bend(spline(-0.011365)).radius;
  const BendBarrier barrier(R);
  const auto stacked_gradient = [&](double turn) {
    const FiberParameterGradient g = barrier.gradient(spline(turn));
    return test::stacked({g.points, g.tangents});
  };
  int swaps = 0;
  double first_where = -1, largest_change = 0;
  Eigen::VectorXd previous = stacked_gradient(-0.01137);
  for (int i = 1; i <= 200; ++i) {
    const double turn = -0.01137 + 1e-5 * i / 200;
    const Eigen::VectorXd g = stacked_gradient(turn);
    ASSERT_GT(g.norm(), 0);
    largest_change = std::max(largest_change, (g - previous).norm() / g.norm());
    previous = g;
    const double where = smallest_bend(spline(turn)).t;
    if (first_where < 0) first_where = where;
    swaps += std::abs(where - first_where) > 0.25;
  }
  EXPECT_GT(swaps, 0); // the sweep does cross from one bend to the other
  EXPECT_LT(largest_change, 1e-3);
  // And at the swap the gradient is the finite differences' of the barrier.
  const HermiteSpline s = spline(-0.011365);
  const test::ScalarFunction f = [&](const Eigen::VectorXd& v) {
    const auto lists = test::unstacked(v, {2, 2});
    return barrier.value(HermiteSpline(lists[0], lists[1]));
  };
  EXPECT_TRUE(test::matches_fd(stacked_gradient(-0.011365),
                               test::fd_gradient(f, test::stacked({s.points(), s.tangents()}), 1e-9)));
}

TEST(BendRadius, BarrierIsEachSpansPeaksLessItsDipsWithinTheBand)
{
  // A cubic Hermite quarter circle bends within 5 % of its radius, its κ rising and falling along
  // each span: with R at 0.99 of its tightest radius every point is in the band, dips too. The
  // barrier is the fixed samples' sum plus, per span, b at each maximum of κ (an end where κ
  // falls from it) less b at each minimum between two, as a scan 300× denser finds them.
  const HermiteSpline arc = quarter_circle(0.02);
  const double R = 0.99 * smallest_bend(arc).radius;
  const BendBarrier bend(R);
  const auto b = [&](double kappa) { return barrier(1 - R * kappa, BendBarrier::kBand); };
  double expected = 0;
  int dips = 0;
  for (int k = 0; k < arc.spans(); ++k) {
    // κ on span k's own side at its end (p'' jumps at a knot).
    const auto on_span = [&](double u) { return curvature(arc, k + std::min(u, 1 - 1e-12)); };
    for (int i = 0; i <= BendBarrier::kSamplesPerSpan; ++i)
      expected += b(on_span(double(i) / BendBarrier::kSamplesPerSpan));
    constexpr int n = 20000;
    std::vector<double> kappa(n + 1);
    for (int i = 0; i <= n; ++i) kappa[i] = on_span(double(i) / n);
    for (int i = 0; i <= n; ++i) {
      const bool above_left = i == 0 || kappa[i] > kappa[i - 1], above_right = i == n || kappa[i] >= kappa[i + 1];
      const bool below_left = i > 0 && kappa[i] < kappa[i - 1], below_right = i < n && kappa[i] <= kappa[i + 1];
      if (above_left && above_right) expected += b(kappa[i]);
      if (below_left && below_right) {
        expected -= b(kappa[i]);
        dips += b(kappa[i]) > 0;
      }
    }
  }
  ASSERT_GT(dips, 0); // dips inside the band: their weight −1 counts
  EXPECT_NEAR(bend.value(arc), expected, 1e-6 * expected);
  // And its gradient is the finite differences'.
  const test::ScalarFunction f = [&](const Eigen::VectorXd& v) {
    const auto lists = test::unstacked(v, {3, 3});
    return bend.value(HermiteSpline(lists[0], lists[1]));
  };
  const FiberParameterGradient g = bend.gradient(arc);
  EXPECT_TRUE(test::matches_fd(test::stacked({g.points, g.tangents}),
                               test::fd_gradient(f, test::stacked({arc.points(), arc.tangents()}), 1e-9)));
}

TEST(BendRadius, BarrierIsInfiniteAtTheRadiusAndZeroFarAboveIt)
{
  const HermiteSpline arc = quarter_circle(0.02);
  EXPECT_EQ(BendBarrier(0.017).value(arc), 0);         // 19.1 mm ≥ 1.11 × 17 mm: out of the band
  EXPECT_GT(BendBarrier(0.018).value(arc), 0);         // 19.1 mm < 1.11 × 18 mm: in the band
  EXPECT_EQ(BendBarrier(0.0195).value(arc), HUGE_VAL); // tighter than asked
  // Two control points bunched into a near-cusp (the tangents no longer fit the 0.5 mm between
  // them): the curve bends through a sub-millimetre radius and the barrier is infinite.
  const HermiteSpline cusp({{0, 0, 0}, {0.05, 0, 0}, {0.0505, 0, 0}, {0.1, 0, 0}},
                           {Eigen::Vector3d(0.05, 0, 0), Eigen::Vector3d(0.03, 0.02, 0),
                            Eigen::Vector3d(0.03, -0.02, 0), Eigen::Vector3d(0.05, 0, 0)});
  EXPECT_LT(smallest_bend(cusp).radius, 1.5e-3);
  EXPECT_EQ(BendBarrier(0.009).value(cusp), HUGE_VAL);
}

TEST(BendRadius, BarrierGradientMatchesFiniteDifferences)
{
  const std::vector<Eigen::Vector3d> P{{0, 0, 0}, {0.03, 0.01, 0.002}, {0.06, -0.005, 0.01}, {0.1, 0, 0}};
  const HermiteSpline s(P);
  const std::vector<Eigen::Vector3d> T = s.tangents();
  const double R = 0.95 * smallest_bend(s).radius; // the tightest bend inside the band
  const BendBarrier barrier(R);
  ASSERT_GT(barrier.value(s), 0);
  ASSERT_LT(barrier.value(s), HUGE_VAL);
  const FiberParameterGradient g = barrier.gradient(s);
  const test::ScalarFunction f = [&](const Eigen::VectorXd& v) {
    const auto lists = test::unstacked(v, {P.size(), T.size()});
    return barrier.value(HermiteSpline(lists[0], lists[1]));
  };
  ASSERT_GT(test::stacked({g.points, g.tangents}).cwiseAbs().maxCoeff(), 0);
  EXPECT_TRUE(
      test::matches_fd(test::stacked({g.points, g.tangents}), test::fd_gradient(f, test::stacked({P, T}), 1e-9)));
}

} // namespace
} // namespace fibermold
