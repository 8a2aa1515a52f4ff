#pragma once
// Quasi-Newton steps on a kept factorization: the L-BFGS two-loop recursion (Nocedal & Wright,
// Numerical Optimization, Algorithm 7.4) with the factorized Hessian of an earlier state as the
// initial inverse H₀⁻¹. The pairs (s, y) of the steps taken since that factorization correct it
// toward the curvature along the path, so that Newton refactorizes less often.

#include <algorithm>
#include <cstddef>
#include <deque>
#include <functional>

#include <Eigen/Core>

namespace fibermold {

class LbfgsCorrection {
public:
  /// Keeps the last `pairs` pairs (none when it is 0 or less).
  explicit LbfgsCorrection(int pairs) : capacity_(static_cast<std::size_t>(std::max(pairs, 0))) {}

  /// Forgets every pair (a new factorization).
  void clear();
  /// Adds the step s = x₊ − x with y = ∇E(x₊) − ∇E(x); skipped unless sᵀy > 0 (the update would
  /// not stay positive definite). Drops the oldest beyond the capacity.
  void add(Eigen::VectorXd s, Eigen::VectorXd y);
  std::size_t size() const { return s_.size(); }

  /// H⁻¹g, H the L-BFGS update of H₀ by the pairs; `initial` applies H₀⁻¹.
  Eigen::VectorXd apply(const Eigen::VectorXd& g,
                        const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& initial) const;

private:
  std::size_t capacity_;
  std::deque<Eigen::VectorXd> s_, y_;
  std::deque<double> rho_; ///< 1 / sᵀy
};

} // namespace fibermold
