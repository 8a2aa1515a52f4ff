#include <cmath>

#include <gtest/gtest.h>

#include "optimize/barrier.hpp"
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
    const double h = 1e-8 * d;
    EXPECT_NEAR((barrier(d + h, dhat) - barrier(d - h, dhat)) / (2 * h), barrier_gradient(d, dhat), 1e-6 * std::abs(barrier_gradient(d, dhat)) + 1e-12);
    EXPECT_NEAR((barrier_gradient(d + h, dhat) - barrier_gradient(d - h, dhat)) / (2 * h), barrier_hessian(d, dhat),
                1e-6 * std::abs(barrier_hessian(d, dhat)) + 1e-9);
    ++checked;
  }
  EXPECT_EQ(checked, 5);
  const PressureBarrier pb{425e3, 20e3};
  EXPECT_EQ(pb.value(200e3), 0);
  EXPECT_GT(pb.value(1e3), 0);
  EXPECT_GT(pb.value(424e3), 0);
  EXPECT_LT(pb.gradient(1e3), 0);  // pushes up from 0
  EXPECT_GT(pb.gradient(424e3), 0);  // and down from p_max
  EXPECT_EQ(pb.value(-1), HUGE_VAL);
}

TEST(FiberCurvature, CircleAndStraightLineAndGradient)
{
  // A straight fiber has no curvature.
  EXPECT_NEAR(fiber_curvature(HermiteSpline({{0, 0, 0}, {0.05, 0, 0}, {0.1, 0, 0}})), 0, 1e-12);
  // A quarter circle of radius r: ∫ κ² ds = (1/r²)(π r / 2) = π / (2 r), within the cubic's accuracy.
  const double r = 0.02, a = r * M_PI / 4;
  const HermiteSpline arc({{r, 0, 0}, {r / std::sqrt(2.0), r / std::sqrt(2.0), 0}, {0, r, 0}},
                          {Eigen::Vector3d(0, a, 0), Eigen::Vector3d(-a, a, 0) / std::sqrt(2.0), Eigen::Vector3d(-a, 0, 0)});
  EXPECT_NEAR(fiber_curvature(arc), M_PI / (2 * r), 0.02 * M_PI / (2 * r));

  const std::vector<Eigen::Vector3d> P{{0, 0, 0}, {0.03, 0.01, 0.002}, {0.06, -0.005, 0.01}, {0.1, 0, 0}};
  const HermiteSpline s(P);
  const std::vector<Eigen::Vector3d> T = s.tangents();
  const FiberParameterGradient g = fiber_curvature_gradient(s);
  const double h = 1e-8;
  double worst = 0, scale = 0;
  for (int which = 0; which < 2; ++which)
    for (std::size_t k = 0; k < P.size(); ++k)
      for (int c = 0; c < 3; ++c) {
        auto p = P, t = T;
        (which ? t : p)[k][c] += h;
        const double plus = fiber_curvature(HermiteSpline(p, t));
        (which ? t : p)[k][c] -= 2 * h;
        const double minus = fiber_curvature(HermiteSpline(p, t));
        const double an = (which ? g.tangents : g.points)[k][c];
        worst = std::max(worst, std::abs((plus - minus) / (2 * h) - an));
        scale = std::max(scale, std::abs(an));
      }
  ASSERT_GT(scale, 0);
  EXPECT_LE(worst, 1e-6 * scale);
}

} // namespace
} // namespace fibermold
