#include "finite_differences.hpp"

#include <algorithm>

namespace fibermold::test {

double central_difference(const ScalarFunction& f, const Eigen::VectorXd& x, const Eigen::VectorXd& d, double h)
{
  return (f(x + h * d) - f(x - h * d)) / (2 * h);
}

Eigen::VectorXd central_difference(const VectorFunction& f, const Eigen::VectorXd& x, const Eigen::VectorXd& d,
                                   double h)
{
  return (f(x + h * d) - f(x - h * d)) / (2 * h);
}

Eigen::VectorXd fd_gradient(const ScalarFunction& f, const Eigen::VectorXd& x, double h)
{
  Eigen::VectorXd g(x.size());
  for (Eigen::Index i = 0; i < x.size(); ++i) g[i] = central_difference(f, x, Eigen::VectorXd::Unit(x.size(), i), h);
  return g;
}

Eigen::MatrixXd fd_jacobian(const VectorFunction& f, const Eigen::VectorXd& x, double h)
{
  Eigen::MatrixXd J;
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    const Eigen::VectorXd column = central_difference(f, x, Eigen::VectorXd::Unit(x.size(), i), h);
    if (i == 0) J.resize(column.size(), x.size());
    J.col(i) = column;
  }
  return J;
}

::testing::AssertionResult matches_fd(const Eigen::MatrixXd& analytic, const Eigen::MatrixXd& fd, double rtol,
                                      double atol)
{
  if (analytic.rows() != fd.rows() || analytic.cols() != fd.cols())
    return ::testing::AssertionFailure() << "sizes differ: " << analytic.rows() << "×" << analytic.cols()
                                         << " analytic, " << fd.rows() << "×" << fd.cols() << " by differences";
  if (analytic.size() == 0) return ::testing::AssertionFailure() << "nothing to compare";
  if (!analytic.allFinite() || !fd.allFinite()) return ::testing::AssertionFailure() << "a derivative is not finite";
  const double error = (analytic - fd).cwiseAbs().maxCoeff(),
               scale = std::max(analytic.cwiseAbs().maxCoeff(), fd.cwiseAbs().maxCoeff());
  if (error <= rtol * scale + atol) return ::testing::AssertionSuccess() << "error " << error << " of " << scale;
  Eigen::Index r = 0, c = 0;
  (analytic - fd).cwiseAbs().maxCoeff(&r, &c);
  return ::testing::AssertionFailure() << "max |analytic − difference| = " << error << " > " << rtol << " × " << scale
                                       << " + " << atol << "; worst at (" << r << ", " << c << "): " << analytic(r, c)
                                       << " analytic, " << fd(r, c) << " by differences";
}

Eigen::VectorXd stacked(const std::vector<std::vector<Eigen::Vector3d>>& lists)
{
  std::vector<double> v;
  for (const auto& list : lists)
    for (const Eigen::Vector3d& p : list) v.insert(v.end(), p.data(), p.data() + 3);
  return Eigen::Map<Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size()));
}

std::vector<std::vector<Eigen::Vector3d>> unstacked(const Eigen::VectorXd& v, const std::vector<std::size_t>& sizes)
{
  std::vector<std::vector<Eigen::Vector3d>> lists;
  Eigen::Index at = 0;
  for (std::size_t n : sizes) {
    auto& list = lists.emplace_back();
    for (std::size_t k = 0; k < n; ++k, at += 3) list.emplace_back(v.segment<3>(at));
  }
  return lists;
}

} // namespace fibermold::test
