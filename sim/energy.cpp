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

std::unique_ptr<HessianProduct> Energy::hessian_at(const Eigen::VectorXd& x) const
{
  class AtState final : public HessianProduct {
  public:
    AtState(const Energy& energy, Eigen::VectorXd x) : energy_(energy), x_(std::move(x)) {}
    void add(const Eigen::VectorXd& v, Eigen::VectorXd& out) const override { energy_.add_hessian_product(x_, v, out); }

  private:
    const Energy& energy_;
    Eigen::VectorXd x_;
  };
  return std::make_unique<AtState>(*this, x);
}

} // namespace fibermold
