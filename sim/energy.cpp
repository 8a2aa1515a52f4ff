#include "sim/energy.hpp"

namespace fibermold {

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
