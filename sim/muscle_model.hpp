#pragma once
// The data-driven McKibben muscle model (paper section VI and appendix): a stress–strain law
// σ(p, ε) that is linear up to ε_max(p) and quadratic beyond (C¹ at the joint), its energy density
// Ψ_act, and pressure-dependent coefficients E(p), A(p) (two-piece lines smoothed with log-cosh)
// and rest strain ε_L(p) (a line).

namespace fibermold {

/// f(p) = a p + b for p ≤ p_i, c p + d beyond (p in Pa); the paper's E(p) and A(p).
struct TwoPieceLine {
  double slope_low, intercept_low, slope_high, intercept_high;
};

/// The smoothed two-piece line of the appendix (eq. 11 smoothed) and its first two derivatives:
///   f(x) = ρ (c − a)/2 ln cosh((x − x_i)/ρ) + (a + c)/2 x + (b + d)/2 + ρ (c − a)/2 ln 2,
///   x_i = −(d − b)/(c − a).
struct Smoothed {
  double value, d1, d2;
};
Smoothed smoothed_two_piece(const TwoPieceLine& line, double x, double rho);

struct MuscleParameters {
  TwoPieceLine stiffness{-549.92, 73.068e6, 26.36, 4.40e6};  ///< E(p), Pa (paper, section VIII)
  TwoPieceLine taut{-23.91e3, 4067.66e6, -986.60, 833.51e6}; ///< A(p), Pa
  double rest_strain_slope = -0.512e-6;                      ///< ε_L(p) = slope p + intercept, 1/Pa
  double rest_strain_intercept = 0;
  double smoothing = 10e3; ///< ρ, Pa
  double diameter = 3e-3;  ///< m

  double area() const;                           ///< A_act = π d² / 4
  double radius() const { return diameter / 2; } ///< m
};

/// Ψ_act(p, ε) and its derivatives in ε and p.
struct MuscleDensity {
  double psi = 0;
  double d_eps = 0, d_eps_eps = 0; ///< σ = ∂Ψ/∂ε and ∂σ/∂ε
  double d_p = 0, d_eps_p = 0, d_p_p = 0;
};

class MuscleModel {
public:
  explicit MuscleModel(MuscleParameters parameters = {}) : m_(parameters) {}
  const MuscleParameters& parameters() const { return m_; }

  /// ε_L(p) = L(p)/L(0) − 1: the free contraction at pressure p (negative).
  double rest_strain(double p) const { return m_.rest_strain_slope * p + m_.rest_strain_intercept; }
  /// ε_max(p) = L(0)/L(p) − 1 = 1/(1 + ε_L) − 1: beyond it the braid is taut.
  double max_strain(double p) const { return 1 / (1 + rest_strain(p)) - 1; }
  Smoothed stiffness(double p) const { return smoothed_two_piece(m_.stiffness, p, m_.smoothing); }
  Smoothed taut(double p) const { return smoothed_two_piece(m_.taut, p, m_.smoothing); }

  /// σ(p, ε) = E ε for ε ≤ ε_max, A ε² + B ε + C beyond, B = E − 2Aε_max, C = Aε_max².
  double stress(double p, double eps) const { return density(p, eps).d_eps; }
  MuscleDensity density(double p, double eps) const;

private:
  MuscleParameters m_;
};

} // namespace fibermold
