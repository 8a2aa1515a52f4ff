#include "optimize/bend_radius.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>
#include <vector>

#include <Eigen/Geometry>

#include "optimize/barrier.hpp"

namespace fibermold {

namespace {

/// p' and p'' on span k at u ∈ [0, 1] (a span's own side at its knots: p'' jumps there), and the
/// weights of P_k, T_k, P_{k+1}, T_{k+1} in them.
struct SpanDerivatives {
  Eigen::Vector3d a, b; ///< p', p''
  double d1[4], d2[4];
};
SpanDerivatives span_derivatives(const HermiteSpline& s, int k, double u)
{
  SpanDerivatives out;
  hermite_derivative_weights(std::clamp(u, 0.0, 1.0), out.d1, out.d2);
  const Eigen::Vector3d* c[4] = {&s.points()[k], &s.tangents()[k], &s.points()[k + 1], &s.tangents()[k + 1]};
  out.a.setZero();
  out.b.setZero();
  for (int m = 0; m < 4; ++m) {
    out.a += out.d1[m] * *c[m];
    out.b += out.d2[m] * *c[m];
  }
  return out;
}

/// κ = |p' × p''| / |p'|³
double curvature_of(const Eigen::Vector3d& a, const Eigen::Vector3d& b)
{
  const double na = a.norm();
  return na > 0 ? a.cross(b).norm() / (na * na * na) : HUGE_VAL;
}

double span_curvature(const HermiteSpline& s, int k, double u)
{
  const SpanDerivatives d = span_derivatives(s, k, u);
  return curvature_of(d.a, d.b);
}

/// Arc length from the start to parameter t, by 8-point chords within t's span.
double arc_length_to(const HermiteSpline& s, double t)
{
  const int k = std::clamp(static_cast<int>(std::floor(t)), 0, s.spans() - 1);
  double length = 0;
  for (int j = 0; j < k; ++j) length += s.span_length(j);
  constexpr int kChords = 8;
  for (int i = 0; i < kChords; ++i)
    length += (s.position(k + (t - k) * (i + 1) / kChords) - s.position(k + (t - k) * i / kChords)).norm();
  return length;
}

/// κ at `per_span` + 1 evenly spaced parameters of span k.
std::vector<double> span_scan(const HermiteSpline& spline, int k, int per_span)
{
  std::vector<double> kappa(static_cast<std::size_t>(per_span) + 1);
  for (int i = 0; i <= per_span; ++i)
    kappa[static_cast<std::size_t>(i)] = span_curvature(spline, k, double(i) / per_span);
  return kappa;
}

/// The extremum of κ (the largest for `sign` +1, the smallest for −1) of span k between lo and hi
/// (u ∈ [0, 1]), by golden-section search to 1e-9 of the span, starting from the scan's κ₀ at u₀.
/// Returns u, κ.
std::pair<double, double> refine_extremum(const HermiteSpline& spline, int k, int sign, double lo, double hi, double u0,
                                          double k0)
{
  const auto f = [&](double u) { return sign * span_curvature(spline, k, u); };
  const double g = (std::sqrt(5.0) - 1) / 2;
  double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
  double f1 = f(x1), f2 = f(x2);
  while (hi - lo > 1e-9) {
    if (f1 > f2) {
      hi = x2, x2 = x1, f2 = f1;
      x1 = hi - g * (hi - lo);
      f1 = f(x1);
    } else {
      lo = x1, x1 = x2, f1 = f2;
      x2 = lo + g * (hi - lo);
      f2 = f(x2);
    }
  }
  if (const double mid = (lo + hi) / 2, f_mid = f(mid); f_mid > sign * k0) return {mid, sign * f_mid};
  return {u0, k0};
}

/// A local extremum of κ along a span: u ∈ [0, 1], κ, and its weight in the bend barrier: +1 for
/// a maximum (a span's end included), −1 for a minimum between two maxima.
struct SpanExtremum {
  double u, kappa;
  int sign;
};

/// The maxima and the minima between them of κ along span k, alternating, a maximum first and
/// last: from the scan `kappa` (span_scan), a rise or fall under 1e-9 of the span's scale (its
/// largest κ, or 1 / its length if larger) taken as level, so that round-off on a straight span or
/// a circular arc makes no extrema. A minimum at a span's end is left out (its weight is 0). The
/// extrema whose scanned κ reaches `refine_above`, and the largest, are refined (refine_extremum)
/// between their scan neighbours: two nearly equal bends are found wherever the scan falls on
/// them.
std::vector<SpanExtremum> span_extrema(const HermiteSpline& spline, int k, const std::vector<double>& kappa,
                                       double refine_above)
{
  const int n = static_cast<int>(kappa.size()) - 1;
  const auto at = [&](int i) { return kappa[static_cast<std::size_t>(i)]; };
  const int largest = static_cast<int>(std::max_element(kappa.begin(), kappa.end()) - kappa.begin());
  const double level = 1e-9 * std::max(at(largest), 1 / std::max(spline.span_length(k), 1e-300));
  std::vector<std::pair<int, int>> found; // scan index, sign
  int candidate = 0, trend = 0;
  for (int i = 1; i <= n; ++i) {
    const double rise = at(i) - at(candidate);
    if (trend == 0) { // level from the span's start so far: a minimum there is an end's
      if (rise < -level)
        found.emplace_back(candidate, +1), trend = -1, candidate = i;
      else if (rise > level)
        trend = +1, candidate = i;
      else if (rise > 0)
        candidate = i;
    } else if (trend > 0) {
      if (rise > 0)
        candidate = i;
      else if (rise < -level)
        found.emplace_back(candidate, +1), trend = -1, candidate = i;
    } else {
      if (rise < 0)
        candidate = i;
      else if (rise > level)
        found.emplace_back(candidate, -1), trend = +1, candidate = i;
    }
  }
  if (trend >= 0) found.emplace_back(candidate, +1); // else the span ends in a minimum: left out
  std::vector<SpanExtremum> out;
  for (const auto& [i, sign] : found) {
    SpanExtremum e{i / double(n), at(i), sign};
    if (at(i) >= refine_above || i == largest) {
      const double lo = std::max(0, i - 1) / double(n), hi = std::min(n, i + 1) / double(n);
      std::tie(e.u, e.kappa) = refine_extremum(spline, k, sign, lo, hi, e.u, e.kappa);
    }
    out.push_back(e);
  }
  return out;
}

/// Where span k bends tightest: the largest of its refined maxima (span_extrema, those within
/// kPeakShare of the scan's largest refined). Returns u ∈ [0, 1], κ.
std::pair<double, double> span_tightest(const HermiteSpline& spline, int k, int per_span)
{
  constexpr double kPeakShare = 0.8;
  const std::vector<double> kappa = span_scan(spline, k, per_span);
  std::pair<double, double> best{0, -1};
  for (const SpanExtremum& e :
       span_extrema(spline, k, kappa, kPeakShare * *std::max_element(kappa.begin(), kappa.end())))
    if (e.sign > 0 && e.kappa > best.second) best = {e.u, e.kappa};
  return best;
}

} // namespace

double curvature(const HermiteSpline& spline, double t)
{
  const int k = std::clamp(static_cast<int>(std::floor(t)), 0, spline.spans() - 1);
  return span_curvature(spline, k, t - k);
}

SmallestBend smallest_bend(const HermiteSpline& spline, int per_span)
{
  double best = 0;
  int best_k = 0;
  double best_u = 0;
  for (int k = 0; k < spline.spans(); ++k)
    if (const auto [u, kappa] = span_tightest(spline, k, per_span); kappa > best) best = kappa, best_k = k, best_u = u;
  SmallestBend out;
  out.t = best_k + best_u;
  // A straight route's κ is round-off (1e-16 of its scale): a radius a million times its length is none.
  out.radius = best * spline.length() > 1e-6 ? 1 / best : HUGE_VAL;
  out.where = spline.position(out.t);
  out.arc_length = arc_length_to(spline, out.t);
  return out;
}

BendBarrier::BendBarrier(double min_radius, double band, int per_span)
    : min_radius_(min_radius), band_(band), per_span_(per_span)
{
}

std::vector<BendBarrier::Sample> BendBarrier::samples(const HermiteSpline& spline, int k) const
{
  std::vector<Sample> out;
  for (int i = 0; i <= per_span_; ++i) out.push_back({double(i) / per_span_, 1});
  // Every extremum that can reach the band is refined; those under half its edge add 0 anyway.
  const double refine_above = 0.5 * (1 - band_) / min_radius_;
  for (const SpanExtremum& e : span_extrema(spline, k, span_scan(spline, k, kTightestScan), refine_above))
    out.push_back({e.u, double(e.sign)});
  return out;
}

double BendBarrier::value(const HermiteSpline& spline) const
{
  double B = 0;
  for (int k = 0; k < spline.spans(); ++k)
    for (const Sample& s : samples(spline, k)) {
      const double b = barrier(1 - min_radius_ * span_curvature(spline, k, s.u), band_);
      if (!std::isfinite(b)) return HUGE_VAL; // at or under the smallest radius
      B += s.weight * b;
    }
  return B;
}

FiberParameterGradient BendBarrier::gradient(const HermiteSpline& spline) const
{
  FiberParameterGradient g;
  g.points.assign(spline.points().size(), Eigen::Vector3d::Zero());
  g.tangents.assign(spline.points().size(), Eigen::Vector3d::Zero());
  for (int k = 0; k < spline.spans(); ++k)
    for (const Sample& s : samples(spline, k)) {
      const SpanDerivatives d = span_derivatives(spline, k, s.u);
      const double kappa = curvature_of(d.a, d.b), h = 1 - min_radius_ * kappa;
      if (h >= band_ || h <= 0) continue;
      // ∂b/∂κ = −R b'(h);  κ = |c| / |a|³, c = a × b:
      //   ∂κ/∂a = (b × c) / (|c| |a|³) − 3 |c| a / |a|⁵,   ∂κ/∂b = (c × a) / (|c| |a|³)
      const Eigen::Vector3d c = d.a.cross(d.b);
      const double nc = c.norm(), na = d.a.norm(), na3 = na * na * na;
      const double by_kappa = -s.weight * min_radius_ * barrier_gradient(h, band_);
      const Eigen::Vector3d by_a = by_kappa * (d.b.cross(c) / (nc * na3) - 3 * nc * d.a / (na3 * na * na));
      const Eigen::Vector3d by_b = by_kappa * c.cross(d.a) / (nc * na3);
      Eigen::Vector3d* out[4] = {&g.points[k], &g.tangents[k], &g.points[k + 1], &g.tangents[k + 1]};
      for (int m = 0; m < 4; ++m) *out[m] += d.d1[m] * by_a + d.d2[m] * by_b;
    }
  return g;
}

} // namespace fibermold
