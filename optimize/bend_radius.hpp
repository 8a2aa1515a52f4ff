#pragma once
// The bend radius of a fiber's centre line and the barrier that keeps it above the muscle's
// smallest: the curvature of a space curve p(t),
//   κ = |p' × p''| / |p'|³,   bend radius r = 1/κ,
// and, with R the smallest bend radius the muscle takes ([muscle] min_bend_radius), h = 1 − R κ,
//   B_bend = Σ_k b(h(t_k), ĥ) + Σ_spans [ Σ_maxima b(h(t_max), ĥ) − Σ_minima b(h(t_min), ĥ) ],
// b the IPC log barrier (barrier.hpp), t_k fixed samples (per_span + 1 per span), and in each span
// the local maxima of κ (its ends included where κ falls from them) and the local minima between
// them. The bracket is ½ (∫|d b(h(t))/dt| dt + b at the span's two ends): the barrier's total
// variation along the span. With one peak it is that peak's b, with several at least the largest's,
// so B is +∞ exactly where the bend radius anywhere reaches R and zero where it is above
// R / (1 − ĥ) (1.11 R). It is smooth where two peaks of nearly equal height swap (a max over them
// is kinked there: a minimizer's smooth model then keeps predicting a decrease across the kink),
// and continuous where a peak and a dip are born together (their b are equal) at a scan point. The
// extrema are found by a scan of kTightestScan points per span, refined: a pair born between two
// scan points enters when the scan resolves it, and B jumps by b(peak) − b(dip) there (up to
// 1.9e-5 on random spans with the dip in the band; κ's critical points are the real roots of a
// degree-7 polynomial per span, which would close that gap). At each extremum
// ∂κ/∂t = 0 (or it sits on a span's end), so its derivative at fixed t is the whole derivative
// (envelope theorem). The barrier thus rises smoothly to the constraint instead of meeting it
// between two samples as a wall a minimizer's step cannot see coming. A cusp (p' = 0) or a loop has
// an unbounded curvature, so two control points that bunch into a near-cusp meet the barrier too.

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
  /// ∂B/∂(points, tangents); the pressure entry is 0. Where B is +∞ the samples at or under R add
  /// nothing (the others still do): a minimizer never asks there.
  FiberParameterGradient gradient(const HermiteSpline& spline) const;
  double min_radius() const { return min_radius_; }

  /// The barrier acts where the radius is under R / (1 − ĥ): 1.11 R.
  static constexpr double kBand = 0.1;
  static constexpr int kSamplesPerSpan = 24;
  /// The scan that finds each span's extrema of κ (then refined by golden section).
  static constexpr int kTightestScan = 64;

private:
  struct Sample {
    double u;      ///< ∈ [0, 1] on its span
    double weight; ///< 1, or −1 at a minimum of κ between two maxima
  };
  /// Span k's samples: per_span + 1 fixed ones and its extrema of κ.
  std::vector<Sample> samples(const HermiteSpline& spline, int k) const;

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
/// The smallest bend radius along the spline: κ scanned at `per_span` parameters per span, each
/// peak within 80 % of a span's highest refined by golden-section search between its neighbours
/// (to 1e-9 of a span), the largest kept.
SmallestBend smallest_bend(const HermiteSpline& spline, int per_span = BendBarrier::kTightestScan);

} // namespace fibermold
