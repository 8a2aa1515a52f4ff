#pragma once
// The C³ MLS weight of the paper (section IV-A) and its derivatives in X:
//   w(d) = 20 s⁷ − 70 s⁶ + 84 s⁵ − 35 s⁴ + 1,  s = d / r ≤ 1;  0 beyond r.

#include <Eigen/Core>

namespace fibermold {

struct MlsWeight {
  double w = 0;
  Eigen::Vector3d grad = Eigen::Vector3d::Zero();
  Eigen::Matrix3d hess = Eigen::Matrix3d::Zero();
};

/// w, ∇w and ∇∇w at X for the node at X_i, with delta = X − X_i.
inline MlsWeight mls_weight(const Eigen::Vector3d& delta, double r)
{
  MlsWeight out;
  const double s = delta.norm() / r;
  if (s >= 1) return out;
  const double s2 = s * s, t = s - 1;
  // Factored, w = (1 − s)⁴ (1 + 4s + 10s² + 20s³): no cancellation near the support's edge.
  out.w = t * t * t * t * (((20 * s + 10) * s + 4) * s + 1);
  // w'(s) = 140 s³ (s − 1)³, so ∇w = g (X − X_i) with g = w'(s) / (r d) = 140 s² (s − 1)³ / r²,
  // and ∇g = h (X − X_i) with h = 140 (s − 1)² (5 s − 2) / r⁴: both smooth at d = 0.
  const double r2 = r * r;
  const double g = 140 * s2 * t * t * t / r2;
  const double h = 140 * t * t * (5 * s - 2) / (r2 * r2);
  out.grad = g * delta;
  out.hess = g * Eigen::Matrix3d::Identity() + h * delta * delta.transpose();
  return out;
}

} // namespace fibermold
