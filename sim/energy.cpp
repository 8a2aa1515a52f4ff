#include "sim/energy.hpp"

namespace fibermold {

void Energy::add_hessian_product(const Eigen::VectorXd& x, const Eigen::VectorXd& v, Eigen::VectorXd& out) const
{
  const auto nodes = x.reshaped(3, x.size() / 3);
  const double extent = (nodes.rowwise().maxCoeff() - nodes.rowwise().minCoeff()).maxCoeff();
  const double h = 1e-6 * extent / v.cwiseAbs().maxCoeff();
  if (!(std::isfinite(h) && h > 0)) {
    if (!v.isZero(0)) out.setConstant(NAN); // an extentless body, or v not finite
    return;
  }
  Eigen::VectorXd forward = Eigen::VectorXd::Zero(x.size()), backward = Eigen::VectorXd::Zero(x.size());
  add_gradient(x + h * v, forward);
  add_gradient(x - h * v, backward);
  out += (forward - backward) / (2 * h);
}

} // namespace fibermold
