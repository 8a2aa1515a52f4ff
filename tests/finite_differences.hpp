#pragma once
// One finite-difference checker for the tests (after ipc-toolkit's finite-diff and polyfem's
// generic form test): central differences of a value, a gradient or any vector function, and one
// tolerance policy for comparing them with the analytic derivative.
//
// The policy: an analytic derivative a matches its central difference d when
//     max |a − d| ≤ rtol · max(max |a|, max |d|) + atol,
// over all entries: the worst entry against the largest. Central differences err by O(h²) (truncation) plus O(ε f / h)
// (round-off); at h ≈ 1e-7 of the variables' scale both are ~1e-7 relative, so rtol = 1e-6 (kFdTolerance) holds for
// smooth terms with a margin of 10. A looser rtol is for differences taken through an iterative solve (an equilibrium),
// and its reason is written beside it. atol covers derivatives that are zero.

#include <functional>
#include <vector>

#include <Eigen/Core>
#include <gtest/gtest.h>

namespace fibermold::test {

/// The relative tolerance for central differences of smooth terms.
constexpr double kFdTolerance = 1e-6;

using ScalarFunction = std::function<double(const Eigen::VectorXd&)>;
using VectorFunction = std::function<Eigen::VectorXd(const Eigen::VectorXd&)>;

/// (f(x + h d) − f(x − h d)) / 2h.
double central_difference(const ScalarFunction& f, const Eigen::VectorXd& x, const Eigen::VectorXd& d, double h);
Eigen::VectorXd central_difference(const VectorFunction& f, const Eigen::VectorXd& x, const Eigen::VectorXd& d,
                                   double h);

/// ∇f by central differences along each coordinate.
Eigen::VectorXd fd_gradient(const ScalarFunction& f, const Eigen::VectorXd& x, double h);
/// The Jacobian of f (the Hessian, for f a gradient) by central differences along each coordinate.
Eigen::MatrixXd fd_jacobian(const VectorFunction& f, const Eigen::VectorXd& x, double h);

/// The policy above, with the worst entry named on failure.
::testing::AssertionResult matches_fd(const Eigen::MatrixXd& analytic, const Eigen::MatrixXd& fd,
                                      double rtol = kFdTolerance, double atol = 0);
inline ::testing::AssertionResult matches_fd(double analytic, double fd, double rtol = kFdTolerance, double atol = 0)
{
  return matches_fd(Eigen::MatrixXd::Constant(1, 1, analytic), Eigen::MatrixXd::Constant(1, 1, fd), rtol, atol);
}

/// Lists of 3-vectors (a spline's points and tangents) as one vector of variables, and back.
Eigen::VectorXd stacked(const std::vector<std::vector<Eigen::Vector3d>>& lists);
std::vector<std::vector<Eigen::Vector3d>> unstacked(const Eigen::VectorXd& v, const std::vector<std::size_t>& sizes);

} // namespace fibermold::test
