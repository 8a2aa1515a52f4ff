#include "sim/muscle_model.hpp"

#include <cmath>

namespace fibermold {

Smoothed smoothed_two_piece(const TwoPieceLine& l, double x, double rho)
{
  const double a = l.slope_low, b = l.intercept_low, c = l.slope_high, d = l.intercept_high;
  if (c == a) return {a * x + std::max(b, d), a, 0}; // one line (the design file rejects distinct parallel ones)
  const double xi = -(d - b) / (c - a);
  const double y = (x - xi) / rho;
  // ln cosh y = |y| + ln(1 + e^{−2|y|}) − ln 2, stable for large |y|
  const double log_cosh = std::abs(y) + std::log1p(std::exp(-2 * std::abs(y))) - std::log(2.0);
  const double t = std::tanh(y);
  Smoothed s;
  s.value = rho * (c - a) / 2 * log_cosh + (a + c) / 2 * x + (b + d) / 2 + rho * (c - a) / 2 * std::log(2.0);
  s.d1 = (c - a) / 2 * t + (a + c) / 2;
  s.d2 = (c - a) / (2 * rho) * (1 - t * t);
  return s;
}

double MuscleParameters::area() const { return M_PI * diameter * diameter / 4; }

MuscleDensity MuscleModel::density(double p, double eps) const
{
  // The paper's Ψ_act with B, C and D as given is, written with u = max(0, ε − ε_max),
  //   Ψ = ½ E ε² + ⅓ A u³
  // (σ = Eε + A u² = Aε² + Bε + C beyond the joint, and Ψ is C² there; D makes it continuous).
  const Smoothed E = stiffness(p), A = taut(p);
  const double one_plus_rest = 1 + rest_strain(p);
  const double s = m_.rest_strain_slope;
  const double em = 1 / one_plus_rest - 1;
  const double em_p = -s / (one_plus_rest * one_plus_rest);
  const double em_pp = 2 * s * s / (one_plus_rest * one_plus_rest * one_plus_rest);
  const double u = std::max(0.0, eps - em);
  MuscleDensity r;
  r.psi = E.value * eps * eps / 2 + A.value * u * u * u / 3;
  r.d_eps = E.value * eps + A.value * u * u;
  r.d_eps_eps = E.value + 2 * A.value * u;
  r.d_p = E.d1 * eps * eps / 2 + A.d1 * u * u * u / 3 - A.value * u * u * em_p;
  r.d_eps_p = E.d1 * eps + A.d1 * u * u - 2 * A.value * u * em_p;
  r.d_p_p = E.d2 * eps * eps / 2 + A.d2 * u * u * u / 3 - 2 * A.d1 * u * u * em_p + 2 * A.value * u * em_p * em_p -
            A.value * u * u * em_pp;
  return r;
}

} // namespace fibermold
