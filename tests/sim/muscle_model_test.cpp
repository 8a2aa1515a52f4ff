#include "sim/muscle_model.hpp"

#include <cmath>

#include <gtest/gtest.h>

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
    const double h = 1.0;
    const Smoothed s = smoothed_two_piece(E, p, rho);
    EXPECT_NEAR((smoothed_two_piece(E, p + h, rho).value - smoothed_two_piece(E, p - h, rho).value) / (2 * h), s.d1, 1e-6 * 600);
    EXPECT_NEAR((smoothed_two_piece(E, p + h, rho).d1 - smoothed_two_piece(E, p - h, rho).d1) / (2 * h), s.d2, 1e-6 * std::abs(s.d2) + 1e-12);
  }
}

TEST(MuscleModel, PaperFitAt425kPa)
{
  const MuscleModel m;
  EXPECT_NEAR(m.rest_strain(425e3), -0.2176, 1e-12);  // contracts by 21.8 %
  EXPECT_NEAR(m.max_strain(425e3), 1 / (1 - 0.2176) - 1, 1e-12);
  EXPECT_NEAR(m.parameters().area(), M_PI * 9e-6 / 4, 1e-18);
  // σ is linear below ε_max and C¹ across it.
  const double em = m.max_strain(300e3);
  const double E = m.stiffness(300e3).value;
  EXPECT_NEAR(m.stress(300e3, 0.5 * em), E * 0.5 * em, 1e-9 * E);
  const double below = m.stress(300e3, em - 1e-9), above = m.stress(300e3, em + 1e-9);
  EXPECT_NEAR(below, above, 1e-6 * std::abs(below));
  EXPECT_GT(m.stress(300e3, em + 0.1), E * (em + 0.1));  // taut: stiffer
}

TEST(MuscleModel, DensityDerivativesMatchFiniteDifferencesAcrossTheJoint)
{
  const MuscleModel m;
  for (double p : {5e3, 80e3, 119e3, 200e3, 425e3}) {  // p ≥ 0: at p = 0, ε = 0 the taut branch starts
    const double em = m.max_strain(p);
    for (double eps : {-0.2, 0.0, em - 0.01, em, em + 1e-4, em + 0.05, 0.4}) {
      const MuscleDensity d = m.density(p, eps);
      const double he = 1e-9, hp = 1e-3;  // small: the third derivative jumps at the joint
      const MuscleDensity e1 = m.density(p, eps + he), e0 = m.density(p, eps - he);
      const MuscleDensity p1 = m.density(p + hp, eps), p0 = m.density(p - hp, eps);
      const auto near = [](double fd, double an, double scale) { EXPECT_NEAR(fd, an, 1e-6 * scale + 1e-9) << fd << " vs " << an; };
      near((e1.psi - e0.psi) / (2 * he), d.d_eps, std::abs(d.d_eps));
      near((e1.d_eps - e0.d_eps) / (2 * he), d.d_eps_eps, std::abs(d.d_eps_eps));
      near((p1.psi - p0.psi) / (2 * hp), d.d_p, std::abs(d.d_p) + 1);
      near((p1.d_eps - p0.d_eps) / (2 * hp), d.d_eps_p, std::abs(d.d_eps_p) + 1);
      near((p1.d_p - p0.d_p) / (2 * hp), d.d_p_p, std::abs(d.d_p_p) + 1e-3);
    }
  }
}

} // namespace
} // namespace fibermold
