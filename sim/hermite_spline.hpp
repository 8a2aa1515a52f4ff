#pragma once
// A muscle fiber's centre line: a cubic Hermite spline through control points P_k with tangents
// T_k (paper section V-A), and its split into straight segments (section VI-A, Fig. 6): segment j
// has vector d_j = e_{j+1} − e_j and centre c_j = (e_j + e_{j+1})/2.

#include <vector>

#include <Eigen/Core>

namespace fibermold {

class HermiteSpline {
public:
  /// Tangents: one per point, as derivatives per unit of the span parameter; empty: Catmull–Rom.
  HermiteSpline(std::vector<Eigen::Vector3d> points, std::vector<Eigen::Vector3d> tangents = {});

  int spans() const { return static_cast<int>(points_.size()) - 1; }
  const std::vector<Eigen::Vector3d>& points() const { return points_; }
  const std::vector<Eigen::Vector3d>& tangents() const { return tangents_; }

  /// Position at t ∈ [0, spans()]: span k = ⌊t⌋ with the Hermite basis h00, h10, h01, h11.
  Eigen::Vector3d position(double t) const;
  /// dp/dt at t.
  Eigen::Vector3d derivative(double t) const;
  /// The Hermite weights of P_k, T_k, P_{k+1}, T_{k+1} at t, and k: position is linear in them.
  void weights(double t, int& span, double w[4]) const;
  /// Arc length, by Gauss–Legendre quadrature on each span.
  double length() const;
  double span_length(int k) const;
  /// Arc length from parameter `from` to `to` (from ≤ to, both in [0, spans()]), the same way.
  double length(double from, double to) const;

private:
  std::vector<Eigen::Vector3d> points_, tangents_;
};

/// The weights of P_k, T_k, P_{k+1}, T_{k+1} in p'(u) and p''(u) at u ∈ [0, 1] of a span.
void hermite_derivative_weights(double u, double d1[4], double d2[4]);

/// Straight segments along a spline: the endpoints' parameters, spread over the spans in
/// proportion to their lengths, `count` segments in all (at least one per span).
struct FiberSegments {
  std::vector<double> t; ///< count + 1 endpoint parameters
  std::vector<Eigen::Vector3d> centres, vectors;
};
FiberSegments split_into_segments(const HermiteSpline& spline, int count);
/// How many segments a spline gets at `per_length` segments per m: ⌈length · per_length⌉, at least one.
int segment_count(const HermiteSpline& spline, double per_length);
/// The endpoint parameters split_into_segments uses; held fixed while the spline's points move, so
/// that segments move smoothly with them.
std::vector<double> segment_parameters(const HermiteSpline& spline, int count);
/// Segments between consecutive parameters t.
FiberSegments segments_at(const HermiteSpline& spline, std::vector<double> t);

} // namespace fibermold
