#include "optimize/skin_barrier.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "optimize/barrier.hpp"
#include "sim/hermite_spline.hpp"

namespace fibermold {

namespace {

/// Each parameter's share of an exit's stretch, s / (2·reach) from the nearer end on the skin (1 or
/// more: outside every exit's stretch), and whether that end is the last. Arc lengths from the
/// chords (fine enough to place it).
struct ExitShare {
  double share = HUGE_VAL;
  bool last = false;
};
std::vector<ExitShare> exit_shares(const SurfaceDistance& skin, const HermiteSpline& spline,
                                   const std::vector<double>& t, double reach)
{
  const double length = spline.length();
  const bool first_on_skin = skin.closest(spline.points().front()).distance < reach;
  const bool last_on_skin = skin.closest(spline.points().back()).distance < reach;
  std::vector<ExitShare> shares;
  double s = 0;
  for (std::size_t k = 0; k < t.size(); ++k) {
    if (k > 0) s += (spline.position(t[k]) - spline.position(t[k - 1])).norm();
    ExitShare e;
    if (first_on_skin) e.share = s / (2 * reach);
    if (last_on_skin && (length - s) / (2 * reach) < e.share) e = {(length - s) / (2 * reach), true};
    shares.push_back(e);
  }
  return shares;
}

/// The parameters among `t` held at d_min, and the exit samples (see exit_samples).
struct ExitSplit {
  std::vector<double> held;
  std::vector<ExitSample> exits;
};
ExitSplit split_at_exits(const SurfaceDistance& skin, const HermiteSpline& spline, const std::vector<double>& t,
                         double reach)
{
  const std::vector<ExitShare> shares = exit_shares(skin, spline, t, reach);
  ExitSplit split;
  for (std::size_t k = 0; k < t.size(); ++k) {
    if (shares[k].share >= 1)
      split.held.push_back(t[k]);
    else if (shares[k].share >= kExitFree)
      split.exits.push_back({t[k], shares[k].share, shares[k].last});
  }
  return split;
}

} // namespace

std::vector<double> parameters_off_exits(const SurfaceDistance& skin, const HermiteSpline& spline,
                                         const std::vector<double>& t, double reach)
{
  return split_at_exits(skin, spline, t, reach).held;
}

std::vector<ExitSample> exit_samples(const SurfaceDistance& skin, const HermiteSpline& spline,
                                     const std::vector<double>& t, double reach)
{
  return split_at_exits(skin, spline, t, reach).exits;
}

SkinBarrier::SkinBarrier(const SurfaceDistance& skin, double min_distance, double band, const HermiteSpline& initial,
                         int samples)
    : skin_(skin), min_(min_distance), band_(band)
{
  ExitSplit split = split_at_exits(skin, initial, segment_parameters(initial, samples), min_distance + band);
  t_ = std::move(split.held);
  exits_ = std::move(split.exits);
  measured_at_.assign(t_.size(), Eigen::Vector3d::Zero());
  measured_.assign(t_.size(), -HUGE_VAL);
}

SkinBarrier::ExitPoint SkinBarrier::exit_point(const ExitSample& e, const HermiteSpline& spline) const
{
  ExitPoint x;
  x.p = spline.position(e.t);
  x.end = e.last ? spline.points().back() : spline.points().front();
  x.from_end = (x.p - x.end).norm();
  // σ = min(1, ρ / (2(d_min + w))), kept off 0, where the ramp and its band would vanish
  x.share = std::clamp(x.from_end / (2 * (min_ + band_)), kShareFloor, 1.0);
  x.ramp = min_ * x.share;
  x.band = band_ * x.share;
  return x;
}

std::optional<ExitShortfall> SkinBarrier::exit_shortfall(const HermiteSpline& spline) const
{
  for (const ExitSample& e : exits_) {
    const ExitPoint x = exit_point(e, spline);
    const SurfaceDistance::Closest c = skin_.closest(x.p);
    const double d = c.inside ? c.distance : -c.distance;
    if (d <= x.ramp) return ExitShortfall{x.p, d, x.ramp, x.from_end};
  }
  return std::nullopt;
}

bool SkinBarrier::beyond_band(std::size_t k, const Eigen::Vector3d& p, SurfaceDistance::Closest& c) const
{
  // The distance to the skin is 1-Lipschitz: d(p) ≥ d(q) − |p − q|.
  if (measured_[k] - (p - measured_at_[k]).norm() >= min_ + band_) return true;
  c = skin_.closest(p);
  measured_at_[k] = p;
  measured_[k] = c.inside ? c.distance : -HUGE_VAL;
  return false;
}

double SkinBarrier::value(const HermiteSpline& spline) const
{
  double B = 0;
  SurfaceDistance::Closest c;
  for (std::size_t k = 0; k < t_.size(); ++k) {
    if (beyond_band(k, spline.position(t_[k]), c)) continue; // b = 0 there
    if (!c.inside) return HUGE_VAL;
    B += barrier((c.distance - min_) / band_, 1.0);
  }
  // The exits' ramp r(ρ), its band shrunk with it.
  for (const ExitSample& e : exits_) {
    const ExitPoint x = exit_point(e, spline);
    const SurfaceDistance::Closest at = skin_.closest(x.p);
    if (!at.inside || at.distance <= x.ramp) return HUGE_VAL;
    B += barrier((at.distance - x.ramp) / x.band, 1.0);
  }
  for (const Dip& dip : dips(spline)) {
    if (!(dip.bottom.d > min_)) return HUGE_VAL;
    B += dip_barrier(dip.bottom.d) - dip_barrier(dip.end.d);
  }
  return B;
}

FiberParameterGradient SkinBarrier::gradient(const HermiteSpline& spline) const
{
  FiberParameterGradient g;
  g.points.assign(spline.points().size(), Eigen::Vector3d::Zero());
  g.tangents.assign(spline.points().size(), Eigen::Vector3d::Zero());
  // ∂/∂p of a term at the spline's point at parameter t, into its control points and tangents.
  const auto add = [&](double t, const Eigen::Vector3d& by_p) {
    int k;
    double w[4];
    spline.weights(t, k, w);
    g.points[k] += w[0] * by_p;
    g.tangents[k] += w[1] * by_p;
    g.points[k + 1] += w[2] * by_p;
    g.tangents[k + 1] += w[3] * by_p;
  };
  SurfaceDistance::Closest c;
  for (std::size_t i = 0; i < t_.size(); ++i) {
    const Eigen::Vector3d p = spline.position(t_[i]);
    if (beyond_band(i, p, c) || !c.inside || c.distance >= min_ + band_) continue;
    // ∂b/∂p = b'((d − d_min)/w)/w ∇d,  ∇d = (p − c)/|p − c| inside the body
    add(t_[i], barrier_gradient((c.distance - min_) / band_, 1.0) / band_ * (p - c.point) / c.distance);
  }
  const double stretch = 2 * (min_ + band_);
  for (const ExitSample& e : exits_) {
    const ExitPoint x = exit_point(e, spline);
    const SurfaceDistance::Closest at = skin_.closest(x.p);
    if (!at.inside || at.distance <= x.ramp || at.distance >= x.ramp + x.band) continue;
    // b((d − d_min σ) / (w σ), 1) = b(d / (w σ) − d_min / w, 1): ∂/∂d = 1/(w σ), ∂/∂σ = −d/(w σ²),
    // σ = ρ / (2(d_min + w)) below 1 and its floor, ρ = |p − p_end|, ∂ρ/∂p = −∂ρ/∂p_end = (p − p_end)/ρ
    const double db = barrier_gradient((at.distance - x.ramp) / x.band, 1.0);
    add(e.t, db / x.band * (x.p - at.point) / at.distance);
    if (x.share <= kShareFloor || x.share >= 1) continue;
    const Eigen::Vector3d by_rho = db * -at.distance / (x.band * x.share) / stretch * (x.p - x.end) / x.from_end;
    add(e.t, by_rho);
    (e.last ? g.points.back() : g.points.front()) -= by_rho;
  }
  // Each dip's term at its bottom less at its end sample, each a point at a fixed parameter: the
  // bottom's parameter moves with the route, but d is stationary along the spline there.
  for (const Dip& dip : dips(spline)) {
    if (!(dip.bottom.d > min_)) break;
    add(dip.bottom.t, dip_barrier_gradient(dip.bottom.d) * dip.bottom.normal);
    add(dip.end.t, -dip_barrier_gradient(dip.end.d) * dip.end.normal);
  }
  return g;
}

double SkinBarrier::dip_barrier(double d) const { return barrier((d - min_) / (kDipBand * band_), 1.0); }

double SkinBarrier::dip_barrier_gradient(double d) const
{
  return barrier_gradient((d - min_) / (kDipBand * band_), 1.0) / (kDipBand * band_);
}

namespace {

/// Where the spline is within one span: its point, and its distance to the skin (inside positive),
/// measured, or a lower bound of it from a sample's last measurement (exact = false).
struct Probe {
  double t;
  Eigen::Vector3d p;
  double d;
  bool exact = true;
  std::size_t sample = 0; ///< which sample, when not exact
};

/// An upper bound of the arc length between parameters a < b of one span: the length of the cubic
/// Bézier control polygon of that piece.
double arc_bound(const HermiteSpline& s, double a, double b)
{
  const double h = b - a;
  const Eigen::Vector3d p0 = s.position(a), p3 = s.position(b);
  const Eigen::Vector3d p1 = p0 + h / 3 * s.derivative(a), p2 = p3 - h / 3 * s.derivative(b); // p' is continuous
  return (p1 - p0).norm() + (p2 - p1).norm() + (p3 - p2).norm();
}

} // namespace

double SkinBarrier::closest_approach(const HermiteSpline& spline, Eigen::Vector3d& where, bool first_only) const
{
  constexpr double kShortest = 1e-6; // m: a piece this short is as close as its ends
  if (t_.empty()) return HUGE_VAL;
  double d = HUGE_VAL;
  const auto keep = [&](const Probe& q) {
    if (q.d < d) d = q.d, where = q.p;
  };
  const auto probe = [&](double t) {
    const Eigen::Vector3d p = spline.position(t);
    const auto c = skin_.closest(p);
    const Probe q{t, p, c.inside ? c.distance : -c.distance};
    keep(q);
    return q;
  };
  // A feasibility test starts the samples from their last measurements (value() keeps them
  // fresh): d ≥ d_last − |p − p_last|, enough to clear most pieces without a query.
  const auto sample = [&](std::size_t k) {
    if (!first_only) return probe(t_[k]);
    const Eigen::Vector3d p = spline.position(t_[k]);
    return Probe{t_[k], p, measured_[k] - (p - measured_at_[k]).norm(), false, k};
  };
  const auto measure = [&](Probe& q) {
    if (q.exact) return;
    if (measured_at_[q.sample] == q.p && measured_[q.sample] > 0) { // measured since, for the piece beside
      q.d = measured_[q.sample];
      q.exact = true;
      return;
    }
    const std::size_t k = q.sample;
    q = probe(q.t);
    measured_at_[k] = q.p;
    measured_[k] = q.d > 0 ? q.d : -HUGE_VAL;
  };
  // Each piece between consecutive samples, cut at the knots.
  std::vector<std::pair<Probe, Probe>> pieces;
  Probe last = sample(0);
  for (std::size_t k = 1; k < t_.size(); ++k) {
    for (double knot = std::floor(last.t) + 1; knot < t_[k]; knot += 1) {
      const Probe at_knot = probe(knot);
      pieces.push_back({last, at_knot});
      last = at_knot;
    }
    const Probe next = sample(k);
    pieces.push_back({last, next});
    last = next;
  }
  if (pieces.empty()) measure(last); // one sample
  // Branch and bound: a piece whose bound clears d_min (or, once a point within d_min is found,
  // the closest so far) holds no point that matters.
  while (!pieces.empty()) {
    auto [a, b] = pieces.back();
    pieces.pop_back();
    if (first_only && d <= min_) return d;
    const double L = arc_bound(spline, a.t, b.t);
    if ((a.d + b.d - L) / 2 > std::min(min_, d)) continue;
    if (!a.exact || !b.exact) { // a bound that does not clear: measure the ends and look again
      measure(a);
      measure(b);
      pieces.push_back({a, b});
      continue;
    }
    if (L < kShortest) continue;
    const Probe m = probe((a.t + b.t) / 2);
    pieces.push_back({a, m});
    pieces.push_back({m, b});
  }
  return d;
}

namespace {

/// f(k, from, to) for each span k's part [from, to] of the parameters a < b, cut at the knots.
template <class F> void for_each_span_part(const HermiteSpline& s, double a, double b, F f)
{
  for (double from = a; from < b;) {
    const int k = std::clamp(static_cast<int>(std::floor(from)), 0, s.spans() - 1);
    const double to = std::min(b, static_cast<double>(k + 1));
    f(k, from, to);
    from = to;
  }
}

/// An upper bound of the arc length between parameters a < b, the pieces cut at the knots.
double length_bound(const HermiteSpline& s, double a, double b)
{
  double L = 0;
  for_each_span_part(s, a, b, [&](int, double from, double to) { L += arc_bound(s, from, to); });
  return L;
}

/// The search for a piece's lowest point leaves a part shorter than this (m of arc), as closest_approach
/// does: within it d is within C·(1 µm)²/8 of its ends, 5e-11 m at d_min = 2.5 mm.
constexpr double kDipShortest = 1e-6;
/// Nor does it pursue a point lower by less than this (m) than the lowest so far: the bound's slack
/// then grows no finer than 1 nm however near d_min the piece lies (a flat piece on a face within
/// 1e-8 mm of d_min took 5 million queries without it).
constexpr double kDipResolution = 1e-9;
/// A bottom must lie this much (relative) below the nearer sample to be a dip: round-off's are not.
constexpr double kDipRoundOff = 1e-12;

/// |p''| on span k at u ∈ [0, 1].
double second_derivative_norm(const HermiteSpline& s, int k, double u)
{
  double d1[4], d2[4];
  hermite_derivative_weights(u, d1, d2);
  return (d2[0] * s.points()[k] + d2[1] * s.tangents()[k] + d2[2] * s.points()[k + 1] + d2[3] * s.tangents()[k + 1])
      .norm();
}

/// C, an upper bound of d'' (in the spline's parameter t) between parameters a < b: d is semiconcave,
/// ∇²d ≤ I/d (the distance to a closed set), so d'' ≤ |p''| + |p'|²/d_min where d ≥ d_min; and on any
/// [u, v] there, d lies above its chord less C(v − u)²/8. (Where the piece comes within d_min the
/// bound still holds at its lowest point, which is all a search for it needs: at the bottom p' ⊥ ∇d.)
/// p'' is linear on a span: |p''| is largest at the ends of each span's part (both sides of a knot);
/// |p'| is at most the larger of its ends' plus max|p''| times half the way between them.
double curvature_bound(const HermiteSpline& s, double a, double b, double d_min)
{
  double p2 = 0;
  for_each_span_part(s, a, b, [&](int k, double from, double to) {
    p2 = std::max({p2, second_derivative_norm(s, k, from - k), second_derivative_norm(s, k, to - k)});
  });
  const double p1 = std::max(s.derivative(a).norm(), s.derivative(b).norm()) + p2 * (b - a) / 2;
  return p2 + p1 * p1 / d_min;
}

/// The spline at t: its distance to the skin (negative outside), and the distance's gradient and
/// its derivative along the spline there.
SkinBarrier::DipPoint dip_point(const SurfaceDistance& skin, const HermiteSpline& spline, double t)
{
  const Eigen::Vector3d p = spline.position(t);
  const auto c = skin.closest(p);
  SkinBarrier::DipPoint q;
  q.t = t;
  q.d = c.inside ? c.distance : -c.distance;
  // ∇d = (p − c)/|p − c| inside, its opposite outside
  q.normal =
      c.distance > 0 ? Eigen::Vector3d((c.inside ? 1.0 : -1.0) * (p - c.point) / c.distance) : Eigen::Vector3d::Zero();
  q.slope = q.normal.dot(spline.derivative(t));
  return q;
}

/// The stationary point of d between lo (d falling) and hi (d rising): the root of the slope by regula
/// falsi (Illinois), halving where the secant leaves the bracket, until the slope is 0 or the bracket
/// closes to round-off; the end nearer the root (the smaller |slope|), whose parameter moves smoothly
/// with the route, so that the envelope theorem gives the gradient.
SkinBarrier::DipPoint slope_root(const SurfaceDistance& skin, const HermiteSpline& spline, SkinBarrier::DipPoint lo,
                                 SkinBarrier::DipPoint hi)
{
  int side = 0; // which end stayed last time: −1 lo, +1 hi
  double slope_lo = lo.slope, slope_hi = hi.slope;
  for (int i = 0; i < 100 && hi.t - lo.t > 1e-15 * std::max(1.0, hi.t); ++i) {
    double t = (lo.t * slope_hi - hi.t * slope_lo) / (slope_hi - slope_lo);
    if (!(t > lo.t && t < hi.t)) t = (lo.t + hi.t) / 2;
    const SkinBarrier::DipPoint q = dip_point(skin, spline, t);
    if (q.slope == 0) return q;
    if (q.slope < 0) {
      lo = q, slope_lo = q.slope;
      if (side == -1) slope_hi /= 2;
      side = -1;
    } else {
      hi = q, slope_hi = q.slope;
      if (side == 1) slope_lo /= 2;
      side = 1;
    }
  }
  return std::abs(lo.slope) <= std::abs(hi.slope) ? lo : hi;
}

/// The bottom of the basin of d that `best` lies in, between `left` and `right` (points with d above
/// best's): downhill from best along its slope to a point where the slope rises through 0, halving
/// toward best where a point is higher but still falling (a ridge of the distance, where its slope
/// drops, lies between), then slope_root on that bracket.
SkinBarrier::DipPoint basin_bottom(const SurfaceDistance& skin, const HermiteSpline& spline, SkinBarrier::DipPoint best,
                                   SkinBarrier::DipPoint left, SkinBarrier::DipPoint right)
{
  for (int i = 0; i < 100 && best.slope != 0; ++i) {
    const bool rightward = best.slope < 0; // downhill
    SkinBarrier::DipPoint& far = rightward ? right : left;
    if (std::abs(far.t - best.t) <= 1e-15 * std::max(1.0, std::abs(best.t))) break;
    if (rightward ? far.slope > 0 : far.slope < 0)
      return rightward ? slope_root(skin, spline, best, far) : slope_root(skin, spline, far, best);
    const SkinBarrier::DipPoint m = dip_point(skin, spline, (best.t + far.t) / 2);
    if (m.d < best.d) { // lower: the search goes on from there
      (rightward ? left : right) = best;
      best = m;
    } else {
      far = m;
    }
  }
  return best;
}

} // namespace

std::vector<SkinBarrier::Dip> SkinBarrier::dips(const HermiteSpline& spline) const
{
  if (spline.points() == dips_points_ && spline.tangents() == dips_tangents_) return dips_; // value(), then gradient()
  std::vector<Dip> out;
  const double reach = min_ + kDipBand * band_;
  for (std::size_t k = 0; k + 1 < t_.size(); ++k) {
    const double a = t_[k], b = t_[k + 1];
    // Lower bounds of d at the two samples from their last measurements (value() keeps them fresh).
    const double da = measured_[k] - (spline.position(a) - measured_at_[k]).norm();
    const double db = measured_[k + 1] - (spline.position(b) - measured_at_[k + 1]).norm();
    if ((da + db - length_bound(spline, a, b)) / 2 >= reach) continue; // no point of the piece within reach
    const double C = curvature_bound(spline, a, b, min_);
    if (std::min(da, db) - C * (b - a) * (b - a) / 8 >= reach) continue;
    const DipPoint pa = dip_point(skin_, spline, a), pb = dip_point(skin_, spline, b);
    const DipPoint& end = pa.d <= pb.d ? pa : pb;
    if (end.d <= min_) continue; // a sample within d_min: the sampled barrier is +∞ there already
    // Branch and bound for the piece's lowest point: a part whose bound clears the lowest point so far
    // (or reach), less kDipTolerance of its height over d_min (at least kDipResolution), or that is
    // shorter than kDipShortest, holds none lower that matters.
    DipPoint best = end;
    std::vector<DipPoint> probed{pa, pb};
    std::vector<std::pair<DipPoint, DipPoint>> parts{{pa, pb}};
    while (!parts.empty() && best.d > min_) {
      const auto [u, v] = parts.back();
      parts.pop_back();
      const double h = v.t - u.t, above = std::min(best.d, reach);
      const double slack = std::max(kDipTolerance * (above - min_), kDipResolution);
      if (std::min(u.d, v.d) - C * h * h / 8 >= above - slack) continue;
      if (length_bound(spline, u.t, v.t) < kDipShortest) continue;
      const DipPoint m = dip_point(skin_, spline, (u.t + v.t) / 2);
      probed.push_back(m);
      if (m.d < best.d) best = m;
      parts.push_back({u, m});
      parts.push_back({m, v});
    }
    dip_probes_ += probed.size();
    // Deeper than round-off (a straight route along a face finds points 1e-18 m lower anywhere, and a
    // bottom there would give the gradient a term the value has not).
    const double deeper = end.d - kDipRoundOff * end.d;
    if (!(best.d < deeper)) continue;
    // Its basin between the nearest points probed on either side (each no lower than it).
    DipPoint left = pa, right = pb;
    for (const DipPoint& q : probed) {
      if (q.t < best.t && q.t > left.t) left = q;
      if (q.t > best.t && q.t < right.t) right = q;
    }
    DipPoint bottom = best.d <= min_ ? best : basin_bottom(skin_, spline, best, left, right);
    if (bottom.d > best.d) bottom = best; // not found below it: the lowest point probed, at its parameter
    if (bottom.d < deeper && bottom.d < reach) out.push_back({bottom, end});
  }
  // A dip within d_min first: value() and gradient() stop there.
  std::stable_partition(out.begin(), out.end(), [&](const Dip& d) { return !(d.bottom.d > min_); });
  dips_points_ = spline.points();
  dips_tangents_ = spline.tangents();
  dips_ = out;
  return out;
}

} // namespace fibermold
