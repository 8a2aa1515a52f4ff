#include "optimize/bend_radius.hpp"

#include <algorithm>
#include <cmath>
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

/// The largest κ of span k between scan points lo and hi (u ∈ [0, 1]), by golden-section search
/// to 1e-9 of the span, starting from the scan's value κ₀ at u₀. Returns u, κ.
std::pair<double, double> refine_peak(const HermiteSpline& spline, int k, double lo, double hi, double u0, double k0)
{
  const double g = (std::sqrt(5.0) - 1) / 2;
  double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
  double f1 = span_curvature(spline, k, x1), f2 = span_curvature(spline, k, x2);
  while (hi - lo > 1e-9) {
    if (f1 > f2) {
      hi = x2, x2 = x1, f2 = f1;
      x1 = hi - g * (hi - lo);
      f1 = span_curvature(spline, k, x1);
    } else {
      lo = x1, x1 = x2, f1 = f2;
      x2 = lo + g * (hi - lo);
      f2 = span_curvature(spline, k, x2);
    }
  }
  if (const double mid = (lo + hi) / 2, k_mid = span_curvature(spline, k, mid); k_mid > k0) return {mid, k_mid};
  return {u0, k0};
}

/// Where span k bends tightest: κ scanned at `per_span` + 1 parameters, and every local maximum of
/// the scan within kPeakShare of its largest refined (refine_peak); the largest refined wins.
/// Refining the scan's largest alone made the barrier jump where two peaks of nearly equal height
/// swap places in the scan (on the twisting bar by 4.6e-5 of an objective of 0.648, which then
/// rejected every step, however short). Returns u ∈ [0, 1], κ.
std::pair<double, double> span_tightest(const HermiteSpline& spline, int k, int per_span)
{
  constexpr double kPeakShare = 0.8;
  constexpr int kMostPeaks = 3; // the highest; a straight span's round-off has peaks everywhere
  std::vector<double> kappa(per_span + 1);
  for (int i = 0; i <= per_span; ++i) kappa[i] = span_curvature(spline, k, double(i) / per_span);
  const double k_max = *std::max_element(kappa.begin(), kappa.end());
  std::vector<int> peaks;
  for (int i = 0; i <= per_span; ++i)
    if ((i == 0 || kappa[i] > kappa[i - 1]) && (i == per_span || kappa[i] >= kappa[i + 1]) &&
        kappa[i] >= kPeakShare * k_max)
      peaks.push_back(i);
  if (peaks.empty()) // a constant κ (a straight span, a circular arc)
    peaks.push_back(static_cast<int>(std::max_element(kappa.begin(), kappa.end()) - kappa.begin()));
  std::stable_sort(peaks.begin(), peaks.end(), [&](int a, int b) { return kappa[a] > kappa[b]; });
  if (peaks.size() > kMostPeaks) peaks.resize(kMostPeaks);
  std::pair<double, double> best{0, -1};
  for (int i : peaks) {
    const double lo = std::max(0, i - 1) / double(per_span), hi = std::min(per_span, i + 1) / double(per_span);
    if (const auto refined = refine_peak(spline, k, lo, hi, i / double(per_span), kappa[i]);
        refined.second > best.second)
      best = refined;
  }
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

std::vector<double> BendBarrier::sample_parameters(const HermiteSpline& spline, int k) const
{
  std::vector<double> u;
  for (int i = 0; i <= per_span_; ++i) u.push_back(double(i) / per_span_);
  u.push_back(span_tightest(spline, k, kTightestScan).first);
  return u;
}

double BendBarrier::value(const HermiteSpline& spline) const
{
  double B = 0;
  for (int k = 0; k < spline.spans(); ++k)
    for (double u : sample_parameters(spline, k)) {
      const double kappa = span_curvature(spline, k, u);
      B += barrier(1 - min_radius_ * kappa, band_); // +∞ at or under the smallest radius
      if (!std::isfinite(B)) return HUGE_VAL;
    }
  return B;
}

FiberParameterGradient BendBarrier::gradient(const HermiteSpline& spline) const
{
  FiberParameterGradient g;
  g.points.assign(spline.points().size(), Eigen::Vector3d::Zero());
  g.tangents.assign(spline.points().size(), Eigen::Vector3d::Zero());
  for (int k = 0; k < spline.spans(); ++k)
    for (double u : sample_parameters(spline, k)) {
      const SpanDerivatives d = span_derivatives(spline, k, u);
      const double kappa = curvature_of(d.a, d.b), h = 1 - min_radius_ * kappa;
      if (h >= band_ || h <= 0) continue;
      // ∂b/∂κ = −R b'(h);  κ = |c| / |a|³, c = a × b:
      //   ∂κ/∂a = (b × c) / (|c| |a|³) − 3 |c| a / |a|⁵,   ∂κ/∂b = (c × a) / (|c| |a|³)
      const Eigen::Vector3d c = d.a.cross(d.b);
      const double nc = c.norm(), na = d.a.norm(), na3 = na * na * na;
      const double by_kappa = -min_radius_ * barrier_gradient(h, band_);
      const Eigen::Vector3d by_a = by_kappa * (d.b.cross(c) / (nc * na3) - 3 * nc * d.a / (na3 * na * na));
      const Eigen::Vector3d by_b = by_kappa * c.cross(d.a) / (nc * na3);
      Eigen::Vector3d* out[4] = {&g.points[k], &g.tangents[k], &g.points[k + 1], &g.tangents[k + 1]};
      for (int m = 0; m < 4; ++m) *out[m] += d.d1[m] * by_a + d.d2[m] * by_b;
    }
  return g;
}

} // namespace fibermold
