#pragma once
// The Rosenbrock valley as the least-squares problem r = (10(x₂ − x₁²), 1 − x₁), minimum (1, 1):
// the model-Hessian minimizers' test problem (levenberg_marquardt_test.cpp, hybrid_minimizer_test.cpp).

#include <Eigen/Core>

namespace fibermold::test {

/// ½|r|², with g = Jᵀr and the Gauss-Newton Hessian B = JᵀJ.
inline double rosenbrock(const Eigen::VectorXd& x, Eigen::VectorXd& g, Eigen::MatrixXd& B)
{
  const Eigen::Vector2d r(10 * (x[1] - x[0] * x[0]), 1 - x[0]);
  Eigen::Matrix2d J;
  J << -20 * x[0], 10, -1, 0;
  g = J.transpose() * r;
  B = J.transpose() * J;
  return 0.5 * r.squaredNorm();
}

/// The same without the model.
inline double rosenbrock_value(const Eigen::VectorXd& x, Eigen::VectorXd& g)
{
  Eigen::MatrixXd B;
  return rosenbrock(x, g, B);
}

} // namespace fibermold::test
