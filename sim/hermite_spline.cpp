#include "sim/hermite_spline.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace fibermold {

HermiteSpline::HermiteSpline(std::vector<Eigen::Vector3d> points, std::vector<Eigen::Vector3d> tangents)
    : points_(std::move(points)), tangents_(std::move(tangents))
{
  const std::size_t n = points_.size();
  if (n < 2) throw std::invalid_argument("a spline needs at least 2 points");
  if (tangents_.empty()) {
    // Catmull–Rom: T_k = (P_{k+1} − P_{k−1}) / 2, one-sided at the ends.
    tangents_.resize(n);
    for (std::size_t k = 0; k < n; ++k) {
      const Eigen::Vector3d& prev = points_[k == 0 ? 0 : k - 1];
      const Eigen::Vector3d& next = points_[k + 1 == n ? n - 1 : k + 1];
      tangents_[k] = (next - prev) / ((k == 0 || k + 1 == n) ? 1.0 : 2.0);
    }
  }
  if (tangents_.size() != n) throw std::invalid_argument("a spline needs one tangent per point");
}

void HermiteSpline::weights(double t, int& span, double w[4]) const
{
  span = std::clamp(static_cast<int>(std::floor(t)), 0, spans() - 1);
  const double u = t - span, u2 = u * u, u3 = u2 * u;
  w[0] = 2 * u3 - 3 * u2 + 1; // h00
  w[1] = u3 - 2 * u2 + u;     // h10
  w[2] = -2 * u3 + 3 * u2;    // h01
  w[3] = u3 - u2;             // h11
}

void hermite_derivative_weights(double u, double d1[4], double d2[4])
{
  const double u2 = u * u;
  d1[0] = 6 * u2 - 6 * u, d1[1] = 3 * u2 - 4 * u + 1, d1[2] = -6 * u2 + 6 * u, d1[3] = 3 * u2 - 2 * u;
  d2[0] = 12 * u - 6, d2[1] = 6 * u - 4, d2[2] = -12 * u + 6, d2[3] = 6 * u - 2;
}

Eigen::Vector3d HermiteSpline::position(double t) const
{
  int k;
  double w[4];
  weights(t, k, w);
  return w[0] * points_[k] + w[1] * tangents_[k] + w[2] * points_[k + 1] + w[3] * tangents_[k + 1];
}

Eigen::Vector3d HermiteSpline::derivative(double t) const
{
  const int k = std::clamp(static_cast<int>(std::floor(t)), 0, spans() - 1);
  double d1[4], d2[4];
  hermite_derivative_weights(t - k, d1, d2);
  return d1[0] * points_[k] + d1[1] * tangents_[k] + d1[2] * points_[k + 1] + d1[3] * tangents_[k + 1];
}

namespace {
/// |p'| integrated with 5-point Gauss–Legendre over [a, b] within one span.
double piece_length(const HermiteSpline& s, double a, double b)
{
  static const double x[5] = {0.0469100770306680, 0.2307653449471585, 0.5, 0.7692346550528415, 0.9530899229693320};
  static const double w[5] = {0.1184634425280945, 0.2393143352496832, 0.2844444444444444, 0.2393143352496832,
                              0.1184634425280945};
  double length = 0;
  for (int i = 0; i < 5; ++i) length += w[i] * s.derivative(a + (b - a) * x[i]).norm();
  return (b - a) * length;
}
} // namespace

double HermiteSpline::span_length(int k) const { return piece_length(*this, k, k + 1); }

double HermiteSpline::length(double from, double to) const
{
  double length = 0;
  for (double a = from; a < to;) {
    const double b = std::min(to, std::floor(a) + 1);
    length += piece_length(*this, a, b);
    a = b;
  }
  return length;
}

double HermiteSpline::length() const
{
  double length = 0;
  for (int k = 0; k < spans(); ++k) length += span_length(k);
  return length;
}

int segment_count(const HermiteSpline& spline, double per_length)
{
  return std::max(1, static_cast<int>(std::ceil(spline.length() * per_length)));
}

FiberSegments split_into_segments(const HermiteSpline& spline, int count)
{
  return segments_at(spline, segment_parameters(spline, count));
}

FiberSegments segments_at(const HermiteSpline& spline, std::vector<double> t)
{
  FiberSegments s;
  s.t = std::move(t);
  for (std::size_t j = 0; j + 1 < s.t.size(); ++j) {
    const Eigen::Vector3d a = spline.position(s.t[j]), b = spline.position(s.t[j + 1]);
    s.centres.push_back((a + b) / 2);
    s.vectors.push_back(b - a);
  }
  return s;
}

std::vector<double> segment_parameters(const HermiteSpline& spline, int count)
{
  const int spans = spline.spans();
  count = std::max(count, spans);
  std::vector<double> lengths(spans);
  double total = 0;
  for (int k = 0; k < spans; ++k) total += lengths[k] = spline.span_length(k);
  // Segments per span ∝ span length, at least one each, summing to count (largest remainders).
  std::vector<int> per(spans, 1);
  std::vector<std::pair<double, int>> share;
  for (int k = 0; k < spans; ++k) {
    const double exact = count * (total > 0 ? lengths[k] / total : 1.0 / spans);
    per[k] = std::max(1, static_cast<int>(std::floor(exact)));
    share.emplace_back(exact - std::floor(exact), k);
  }
  int assigned = 0;
  for (int k = 0; k < spans; ++k) assigned += per[k];
  std::sort(share.rbegin(), share.rend());
  for (int i = 0; assigned < count; ++i, ++assigned) ++per[share[i % spans].second];
  for (int k = 0; assigned > count; k = (k + 1) % spans) // the minimum of one per span overshot
    if (per[k] > 1) {
      --per[k];
      --assigned;
    }

  std::vector<double> t;
  for (int k = 0; k < spans; ++k)
    for (int j = 0; j < per[k]; ++j) t.push_back(k + static_cast<double>(j) / per[k]);
  t.push_back(spans);
  return t;
}

} // namespace fibermold
