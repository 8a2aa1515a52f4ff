#pragma once
// The skin barrier of section V-B: keeps every sample of a fiber at least d_min (the muscle radius
// + [collide] clearance) inside the outside surface of the undeformed body,
//   B = Σ_k b((d_k − d_min) / w, 1),
// with b the IPC log barrier (barrier.hpp), d_k the distance of sample p_k to the skin (AABB
// tree), w the band over which the barrier acts; B = +∞ once a sample comes closer than d_min.
// Samples sit at fixed spline parameters, so p_k is linear in the control points and tangents.
// Samples near an end point that lies within d_min + w of the skin (within 2(d_min + w) of arc from
// it on the starting route) are not held at d_min: the fiber leaves the body there by design. They
// are held instead at a distance that grows with their distance ρ from that end on the route as it
// is now, the exit ramp
//   r(ρ) = d_min · σ,   with the band w · σ,   σ = min(1, ρ / (2(d_min + w))),
// which a route leaving a flat face within acos(d_min / (2(d_min + w))) of its normal (72° at the
// defaults) clears: a point at ρ from the exit along a line θ off the normal lies ρ cos θ deep, and
// meets the ramp at cos θ = d_min / (2(d_min + w)), however far along the line an exit sample has
// moved; the band's share makes the term 0 for a route within 60° of the normal. Until session 42 they were
// left out, and a new user's optimized muscle left its base face 92° off the normal, running along
// the face half outside the body for 5 mm with nothing said. Until session 43 σ was each sample's
// share of the starting route's arc, fixed: a lengthened end tangent carried a sample further out
// than its share said, and three times the tangent let 84° pass. The samples within a tenth of the
// stretch of the end on the starting route (r under d_min / 10 there) stay free: the exit itself.
// Which samples are the exit's is still chosen on the starting route: the free ones stay free where
// a lengthened tangent carries them (three times it: to about 0.3 of the stretch), and the held ones
// stay at d_min where a shortened one brings them within the stretch (at 70° off the normal, one
// brought to 7 mm of the end is refused: it is 2.4 mm deep). σ has a corner at 1 (the term is C⁰ in
// ρ there, where a steep exit's sample may be in its band).
// Between samples the spline is held to d_min exactly (closest_approach): the distance to the skin
// is 1-Lipschitz, so on a piece of arc length ≤ L between points at distances d_a and d_b every
// point is at least (d_a + d_b − L)/2 from the skin; L is bounded by the piece's Bézier control
// polygon. Pieces that bound cannot clear d_min (or, once a point within d_min is found, the
// closest so far) are halved until they are shorter than a micrometre. A route through a notch, whose bottom
// lies between two samples, is caught there.
// So that B rises to +∞ where that test refuses, and not only at the samples, each piece between
// samples k and k + 1 whose spline comes closer to the skin than either sample adds a dip term
//   b((d*_k − d_min) / (εw), 1) − b((min(d_k, d_k+1) − d_min) / (εw), 1),   ε = kDipBand,
// d*_k the piece's smallest distance, its bottom. d is semiconcave (d'' ≤ C, curvature_bound), so on
// a part [u, v] of the piece d ≥ min(d_u, d_v) − C(v − u)²/8: branch and bound on that finds the
// lowest point (to kDipTolerance of its height over d_min, exactly at d_min), and regula falsi on d's
// slope along the spline, ∇d·p'(t), the bottom of its basin, where the slope is 0. The term is 0
// where the bottom reaches a sample and beyond εw of d_min, so B stays continuous; by the envelope
// theorem its gradient is that of the two points at fixed parameters. Without it the optimizer met the
// wall between samples as a jump to +∞ that no gradient foretold: a finger pressed against its
// flat underside stopped there, every step of BFGS and Levenberg-Marquardt refused, |∇f| = 92.
// The same Lipschitz bound spares most distance queries: a sample whose last measured distance, less
// how far it has moved since, is still beyond d_min + w adds exactly 0 to B and to its gradient (and
// is inside), so value() and gradient() query the skin only for samples that may be in the band,
// and closest_approach's feasibility test (first_only) starts each sample's piece from that bound,
// measuring only where it does not clear d_min (the tentacle tip's optimize: 40.0–42.4 s → 36.7–37.5 s
// in two interleaved runs each, the same routes).

#include <optional>
#include <vector>

#include "mesh/surface_distance.hpp"
#include "sim/hermite_spline.hpp"
#include "sim/muscle_energy.hpp"

namespace fibermold {

/// The parameters among `t` that are held away from the skin: all but those within 2·reach of arc
/// length of an end that lies within `reach` of the skin, where the fiber leaves the body by design.
std::vector<double> parameters_off_exits(const SurfaceDistance& skin, const HermiteSpline& spline,
                                         const std::vector<double>& t, double reach);

/// A sample of an exit's stretch: its parameter, its share of the stretch on the route it was
/// chosen on, s / (2·reach) of arc from the end it is nearer (in [kExitFree, 1)), and whether that
/// end is the last.
struct ExitSample {
  double t = 0, share = 0;
  bool last = false;
};
/// The samples among `t` within 2·reach of arc of an end that lies within `reach` of the skin, at
/// least kExitFree of that from it.
std::vector<ExitSample> exit_samples(const SurfaceDistance& skin, const HermiteSpline& spline,
                                     const std::vector<double>& t, double reach);
/// The share of an exit's stretch next to the end where a sample is left free (the exit itself).
inline constexpr double kExitFree = 0.1;

/// Where an exit sample comes closer to the skin than its ramp: the point, its distance to the skin
/// (negative outside), the ramp's distance there r(ρ), and its distance ρ from the end.
struct ExitShortfall {
  Eigen::Vector3d where = Eigen::Vector3d::Zero();
  double distance = 0, required = 0, from_end = 0;
};

/// The spline parameters [first, last] a skin barrier holds off the skin; first > last: none.
struct HeldStretch {
  double first = 0, last = 0;
  bool holds(double t) const { return first <= t && t <= last; }
};

/// The part of the band, nearest d_min, over which a dip between samples adds to the barrier.
inline constexpr double kDipBand = 0.05;
/// The search for a piece's lowest point passes over a part whose bound clears the lowest point so
/// far less this much of that point's height over d_min: exact at d_min, where the barrier is +∞.
inline constexpr double kDipTolerance = 1e-3;

class SkinBarrier {
public:
  /// `samples` parameters spread by arc length over `initial`, which fixes the excluded ends.
  SkinBarrier(const SurfaceDistance& skin, double min_distance, double band, const HermiteSpline& initial, int samples);

  double value(const HermiteSpline& spline) const;
  /// ∂B/∂(points, tangents); the pressure entry is 0. Zero where B is +∞.
  FiberParameterGradient gradient(const HermiteSpline& spline) const;
  /// The smallest distance to the skin (m) of the spline between its first and last sample,
  /// negative when outside, and where: exact (to a micrometre of arc) where it is d_min or less;
  /// above d_min, the smallest of the samples and of the points probed between them.
  /// `first_only`: stop at the first point found within d_min (a feasibility test); above d_min the
  /// value is then only a bound (samples whose last distance clears d_min are not measured again,
  /// and it may be +∞ with `where` unset).
  double closest_approach(const HermiteSpline& spline, Eigen::Vector3d& where, bool first_only = false) const;
  /// The first exit sample closer to the skin than its ramp r(ρ) allows (or outside), if any.
  std::optional<ExitShortfall> exit_shortfall(const HermiteSpline& spline) const;
  /// The exit samples (exit_samples).
  const std::vector<ExitSample>& exits() const { return exits_; }
  /// Where along the spline the barrier holds: from its first sample to its last. Collide tests
  /// the skin over the same parameters (FiberClearance), so the two agree on where an end's
  /// stretch leaves the body by design, however the route has moved since.
  HeldStretch held() const { return t_.empty() ? HeldStretch{1, 0} : HeldStretch{t_.front(), t_.back()}; }
  /// The samples' spline parameters.
  const std::vector<double>& samples() const { return t_; }

  /// A point of the spline: its parameter, distance to the skin d (negative outside), ∇d there
  /// and d's derivative along the spline, dd/dt.
  struct DipPoint {
    double t = 0, d = 0, slope = 0;
    Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  };
  /// Where the spline comes closer to the skin between two samples than at either: the bottom,
  /// and the nearer of the two samples.
  struct Dip {
    DipPoint bottom, end;
  };
  /// The dips whose bottom lies within d_min + kDipBand·w, a dip within d_min first.
  std::vector<Dip> dips(const HermiteSpline& spline) const;
  /// The points dips()'s branch and bound has probed so far (each a distance query): its cost.
  std::size_t dip_probes() const { return dip_probes_; }

private:
  /// Whether sample k, now at p, is provably beyond the band (see above); if not, measures it and
  /// returns its skin distance in `c`.
  bool beyond_band(std::size_t k, const Eigen::Vector3d& p, SurfaceDistance::Closest& c) const;
  /// b((d − d_min) / (kDipBand·w), 1) and its derivative in d.
  double dip_barrier(double d) const;
  double dip_barrier_gradient(double d) const;
  /// An exit sample on a spline: its point, its end's, its distance from that end ρ, its share of
  /// the stretch σ (see above) and the ramp r = d_min·σ and band w·σ there.
  struct ExitPoint {
    Eigen::Vector3d p, end;
    double from_end = 0, share = 0, ramp = 0, band = 0;
  };
  ExitPoint exit_point(const ExitSample& e, const HermiteSpline& spline) const;
  /// The least share σ: a sample on its end would have neither ramp nor band.
  static constexpr double kShareFloor = 1e-6;

  const SurfaceDistance& skin_;
  double min_, band_;
  std::vector<double> t_;
  std::vector<ExitSample> exits_;
  /// Each sample where its distance was last measured, and that distance (−∞: outside).
  mutable std::vector<Eigen::Vector3d> measured_at_;
  mutable std::vector<double> measured_;
  /// The last spline dips() searched, and what it found.
  mutable std::vector<Eigen::Vector3d> dips_points_, dips_tangents_;
  mutable std::vector<Dip> dips_;
  mutable std::size_t dip_probes_ = 0;
};

} // namespace fibermold
