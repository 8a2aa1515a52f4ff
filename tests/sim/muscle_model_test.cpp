#include "sim/muscle_model.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "finite_differences.hpp"

namespace fibermold {
namespace {

TEST(SmoothedTwoPieceLine, FollowsItsAsymptotesAndItsDerivatives)
{
  const TwoPieceLine E{-549.92, 73.068e6, 26.36, 4.40e6};
  const double rho = 10e3;
  // Far from the kink (at 119.2 kPa) the smoothed line is the line itself.
  EXPECT_NEAR(smoothed_two_piece(E, 0, rho).value, 73.068e6, 1e-6 * 73.068e6);
  EXPECT_NEAR(smoothed_two_piece(E, 425e3, rho).value, 26.36 * 425e3 + 4.40e6, 1e-6 * 15.6e6);
  EXPECT_NEAR(smoothed_two_piece(E, 425e3, rho).d1, 26.36, 1e-9);
  for (double p : {0.0, 100e3, 119.2e3, 125e3, 300e3}) {
    const Smoothed s = smoothed_two_piece(E, p, rho);
    const Eigen::VectorXd x = Eigen::VectorXd::Constant(1, p), one = Eigen::VectorXd::Ones(1);
    const test::ScalarFunction value = [&](const Eigen::VectorXd& q) { return smoothed_two_piece(E, q[0], rho).value; };
    const test::ScalarFunction d1 = [&](const Eigen::VectorXd& q) { return smoothed_two_piece(E, q[0], rho).d1; };
    // 1 Pa steps on pressures of 1e5 Pa; the slopes are of order 600 (Pa/Pa), a value of 1e7 Pa.
    EXPECT_TRUE(test::matches_fd(s.d1, test::central_difference(value, x, one, 1.0), 0, 1e-6 * 600)) << p;
    EXPECT_TRUE(test::matches_fd(s.d2, test::central_difference(d1, x, one, 1.0), test::kFdTolerance, 1e-12)) << p;
  }
}

TEST(MuscleModel, PaperFitAt425kPa)
{
  const MuscleModel m;
  EXPECT_NEAR(m.rest_strain(425e3), -0.2176, 1e-12); // contracts by 21.8 %
  EXPECT_NEAR(m.max_strain(425e3), 1 / (1 - 0.2176) - 1, 1e-12);
  EXPECT_NEAR(m.parameters().area(), M_PI * 9e-6 / 4, 1e-18);
  // σ is linear below ε_max and C¹ across it.
  const double em = m.max_strain(300e3);
  const double E = m.stiffness(300e3).value;
  EXPECT_NEAR(m.stress(300e3, 0.5 * em), E * 0.5 * em, 1e-9 * E);
  const double below = m.stress(300e3, em - 1e-9), above = m.stress(300e3, em + 1e-9);
  EXPECT_NEAR(below, above, 1e-6 * std::abs(below));
  EXPECT_GT(m.stress(300e3, em + 0.1), E * (em + 0.1)); // taut: stiffer
}

TEST(MuscleModel, DensityDerivativesMatchFiniteDifferencesAcrossTheJoint)
{
  const MuscleModel m;
  for (double p : {5e3, 80e3, 119e3, 200e3, 425e3}) { // p ≥ 0: at p = 0, ε = 0 the taut branch starts
    const double em = m.max_strain(p);
    for (double eps : {-0.2, 0.0, em - 0.01, em, em + 1e-4, em + 0.05, 0.4}) {
      const MuscleDensity d = m.density(p, eps);
      const double he = 1e-9, hp = 1e-3; // small: the third derivative jumps at the joint
      const Eigen::VectorXd x = Eigen::Vector2d(p, eps), along_p = Eigen::Vector2d(1, 0),
                            along_eps = Eigen::Vector2d(0, 1);
      const auto of = [&](double MuscleDensity::*field) -> test::ScalarFunction {
        return [&m, field](const Eigen::VectorXd& y) { return m.density(y[0], y[1]).*field; };
      };
      const auto check = [&](double analytic, double fd, double floor) {
        EXPECT_TRUE(test::matches_fd(analytic, fd, test::kFdTolerance, 1e-6 * floor + 1e-9))
            << "p " << p << ", ε " << eps;
      };
      check(d.d_eps, test::central_difference(of(&MuscleDensity::psi), x, along_eps, he), 0);
      check(d.d_eps_eps, test::central_difference(of(&MuscleDensity::d_eps), x, along_eps, he), 0);
      check(d.d_p, test::central_difference(of(&MuscleDensity::psi), x, along_p, hp), 1);
      check(d.d_eps_p, test::central_difference(of(&MuscleDensity::d_eps), x, along_p, hp), 1);
      check(d.d_p_p, test::central_difference(of(&MuscleDensity::d_p), x, along_p, hp), 1e-3);
    }
  }
}

} // namespace
} // namespace fibermold
