#include "optimize/skin_barrier.hpp"

#include <cmath>
#include <utility>

#include "optimize/barrier.hpp"

namespace fibermold {

std::vector<double> parameters_off_exits(const SurfaceDistance& skin, const HermiteSpline& spline,
                                         const std::vector<double>& t, double reach)
{
  const double length = spline.length();
  const bool first_on_skin = skin.closest(spline.points().front()).distance < reach;
  const bool last_on_skin = skin.closest(spline.points().back()).distance < reach;
  std::vector<double> kept;
  // Arc length at each parameter, from the chords (fine enough to place the cut-off).
  double s = 0;
  for (std::size_t k = 0; k < t.size(); ++k) {
    if (k > 0) s += (spline.position(t[k]) - spline.position(t[k - 1])).norm();
    if (first_on_skin && s < 2 * reach) continue;
    if (last_on_skin && length - s < 2 * reach) continue;
    kept.push_back(t[k]);
  }
  return kept;
}

SkinBarrier::SkinBarrier(const SurfaceDistance& skin, double min_distance, double band, const HermiteSpline& initial,
                         int samples)
    : skin_(skin), min_(min_distance), band_(band),
      t_(parameters_off_exits(skin, initial, segment_parameters(initial, samples), min_distance + band)),
      measured_at_(t_.size(), Eigen::Vector3d::Zero()), measured_(t_.size(), -HUGE_VAL)
{
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
  return B;
}

FiberParameterGradient SkinBarrier::gradient(const HermiteSpline& spline) const
{
  FiberParameterGradient g;
  g.points.assign(spline.points().size(), Eigen::Vector3d::Zero());
  g.tangents.assign(spline.points().size(), Eigen::Vector3d::Zero());
  SurfaceDistance::Closest c;
  for (std::size_t i = 0; i < t_.size(); ++i) {
    const double t = t_[i];
    const Eigen::Vector3d p = spline.position(t);
    if (beyond_band(i, p, c) || !c.inside || c.distance >= min_ + band_) continue;
    // ∂b/∂p = b'((d − d_min)/w)/w ∇d,  ∇d = (p − c)/|p − c| inside the body
    const Eigen::Vector3d by_p =
        barrier_gradient((c.distance - min_) / band_, 1.0) / band_ * (p - c.point) / c.distance;
    int k;
    double w[4];
    spline.weights(t, k, w);
    g.points[k] += w[0] * by_p;
    g.tangents[k] += w[1] * by_p;
    g.points[k + 1] += w[2] * by_p;
    g.tangents[k + 1] += w[3] * by_p;
  }
  return g;
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

} // namespace fibermold
