#include "sim/lbfgs_correction.hpp"

#include <vector>

namespace fibermold {

void LbfgsCorrection::clear()
{
  s_.clear();
  y_.clear();
  rho_.clear();
}

void LbfgsCorrection::add(Eigen::VectorXd s, Eigen::VectorXd y)
{
  if (capacity_ == 0) return;
  const double sy = s.dot(y);
  if (!(sy > 1e-10 * s.norm() * y.norm())) return;
  s_.push_back(std::move(s));
  y_.push_back(std::move(y));
  rho_.push_back(1 / sy);
  if (s_.size() > capacity_) {
    s_.pop_front();
    y_.pop_front();
    rho_.pop_front();
  }
}

Eigen::VectorXd LbfgsCorrection::apply(const Eigen::VectorXd& g,
                                       const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& initial) const
{
  // Algorithm 7.4: q ← g; newest to oldest αᵢ = ρᵢ sᵢᵀq, q ← q − αᵢ yᵢ; r = H₀⁻¹q; oldest to newest
  // β = ρᵢ yᵢᵀr, r ← r + sᵢ (αᵢ − β).
  Eigen::VectorXd q = g;
  std::vector<double> alpha(s_.size());
  for (std::size_t i = s_.size(); i-- > 0;) {
    alpha[i] = rho_[i] * s_[i].dot(q);
    q -= alpha[i] * y_[i];
  }
  Eigen::VectorXd r = initial(q);
  for (std::size_t i = 0; i < s_.size(); ++i) r += s_[i] * (alpha[i] - rho_[i] * y_[i].dot(r));
  return r;
}

} // namespace fibermold
