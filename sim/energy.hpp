#pragma once
// One interface for every term of the total potential energy (after polyfem's Form): value,
// gradient, Hessian, and a line-search hook that rejects invalid states.

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "sim/sparse_hessian.hpp"

namespace fibermold {

/// An energy's exact Hessian at one state as an operator, for the many products conjugate
/// gradients take at one x: what the state alone decides is worked out once.
class HessianProduct {
public:
  virtual ~HessianProduct() = default;
  /// out += ∂²E/∂x²(x) v
  virtual void add(const Eigen::VectorXd& v, Eigen::VectorXd& out) const = 0;
};

class Energy {
public:
  virtual ~Energy() = default;
  virtual std::string name() const = 0;
  /// E(x) for node positions x stacked as 3n (m).
  virtual double value(const Eigen::VectorXd& x) const = 0;
  /// g += ∂E/∂x
  virtual void add_gradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const = 0;
  /// H += ∂²E/∂x²; with `project`, each local contribution is projected to positive semi-definite.
  virtual void add_hessian(const Eigen::VectorXd& x, SparseHessian& H, bool project) const = 0;
  /// out += ∂²E/∂x² v, the exact Hessian's product (never projected, no pair lumped): what
  /// conjugate gradients on the adjoint ask, at one x for many v; in closed form. (Until session
  /// 36 a muscle's was a central difference of add_gradient, 1e-6 relative.)
  virtual void add_hessian_product(const Eigen::VectorXd& x, const Eigen::VectorXd& v, Eigen::VectorXd& out) const = 0;
  /// The same products at one x (x is copied). By default each is add_hessian_product(x, v, out);
  /// the elastic energy keeps each point's F⁻ᵀ and ln J, a muscle each chord's 3 × 3 block.
  virtual std::unique_ptr<HessianProduct> hessian_at(const Eigen::VectorXd& x) const;
  /// Node sets coupled by this energy (the Hessian's sparsity pattern).
  virtual void stencils(std::vector<std::vector<int>>& out) const = 0;
  /// False for a state the energy is not defined at (e.g. an inverted element).
  virtual bool is_step_valid(const Eigen::VectorXd&) const { return true; }
  /// E(x) with g += ∂E/∂x, or +∞ (g then partly updated) where !is_step_valid(x): what a line
  /// search asks of each trial state, in one pass where the terms share their work.
  virtual double value_and_gradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const
  {
    if (!is_step_valid(x)) return HUGE_VAL;
    add_gradient(x, g);
    return value(x);
  }
};

} // namespace fibermold
