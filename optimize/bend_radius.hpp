#pragma once
// The bend radius of a fiber's centre line and the barrier that keeps it above the muscle's
// smallest: the curvature of a space curve p(t),
//   κ = |p' × p''| / |p'|³,   bend radius r = 1/κ,
// and, with R the smallest bend radius the muscle takes ([muscle] min_bend_radius),
//   B_bend = Σ_k b(1 − R κ(t_k), ĥ),
// b the IPC log barrier (barrier.hpp) at the spline parameters t_k: fixed samples, and in each span
// the parameter where it bends tightest (smallest_bend's search): +∞ exactly where the bend radius
// anywhere reaches R, zero where it is above R / (1 − ĥ) (1.11 R). At that moving sample ∂κ/∂t = 0
// (or it sits on a span's end), so its derivative at fixed t is the whole derivative (envelope
// theorem). The barrier thus rises smoothly to the constraint instead of meeting it between two
// samples as a wall a minimizer's step cannot see coming. A cusp (p' = 0) or a loop has an
// unbounded curvature, so two control points that bunch into a near-cusp meet the barrier too.

#include <vector>

#include <Eigen/Core>

#include "sim/hermite_spline.hpp"
#include "sim/muscle_energy.hpp"

namespace fibermold {

/// The default smallest bend radius of a muscle, in diameters ([muscle] min_bend_radius): 6 mm for
/// the default 3 mm muscle. No bend-radius figure is published for thin McKibben muscles; a tube
/// bent through less than about its diameter pinches its bore, and two diameters leaves a margin
/// for the braid. docs/optimize.md says how to measure a muscle's own.
inline constexpr double kBendRadiusPerDiameter = 2;

/// κ(t) of a spline.
double curvature(const HermiteSpline& spline, double t);

class BendBarrier {
public:
  /// `min_radius` R (m), the band ĥ (0 < ĥ < 1) and the samples per span.
  BendBarrier(double min_radius, double band = kBand, int per_span = kSamplesPerSpan);

  double value(const HermiteSpline& spline) const;
  /// ∂B/∂(points, tangents); the pressure entry is 0. Zero where B is +∞.
  FiberParameterGradient gradient(const HermiteSpline& spline) const;
  double min_radius() const { return min_radius_; }

  /// The barrier acts where the radius is under R / (1 − ĥ): 1.11 R.
  static constexpr double kBand = 0.1;
  static constexpr int kSamplesPerSpan = 24;
  /// The scan that finds each span's tightest point (then refined by golden section).
  static constexpr int kTightestScan = 64;

private:
  /// Span k's sample parameters u ∈ [0, 1]: per_span + 1 fixed ones and the tightest point.
  std::vector<double> sample_parameters(const HermiteSpline& spline, int k) const;

  double min_radius_, band_;
  int per_span_;
};

/// Where a spline bends tightest.
struct SmallestBend {
  double radius = HUGE_VAL; ///< m; +∞ for a straight spline (a radius over 1e6 × its length)
  double t = 0;             ///< spline parameter
  Eigen::Vector3d where = Eigen::Vector3d::Zero();
  double arc_length = 0; ///< m from the first point
};
/// The smallest bend radius along the spline: κ scanned at `per_span` parameters per span, the
/// largest refined by golden-section search between its neighbours (to 1e-9 of a span).
SmallestBend smallest_bend(const HermiteSpline& spline, int per_span = BendBarrier::kTightestScan);

} // namespace fibermold
