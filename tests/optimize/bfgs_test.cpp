// BFGS with LBFGSpp's line search: the Rosenbrock valley to 1e-6, and a wall of +∞ (a failed
// simulation) that the line search backs away from.
#include <cmath>

#include <gtest/gtest.h>

#include "optimize/bfgs.hpp"

namespace fibermold {
namespace {

double rosenbrock(const Eigen::VectorXd& x, Eigen::VectorXd& g)
{
  g.resize(2);
  g[0] = -2 * (1 - x[0]) - 400 * x[0] * (x[1] - x[0] * x[0]);
  g[1] = 200 * (x[1] - x[0] * x[0]);
  return (1 - x[0]) * (1 - x[0]) + 100 * (x[1] - x[0] * x[0]) * (x[1] - x[0] * x[0]);
}

TEST(Bfgs, FindsTheRosenbrockMinimum)
{
  NullProgress progress;
  BfgsOptions o;
  o.gradient_tolerance = 1e-8;
  o.relative_tolerance = 0;
  int callbacks = 0;
  const BfgsResult r = minimize_bfgs(rosenbrock, Eigen::Vector2d(-1.2, 1), o,
                                     [&](const BfgsIteration& it, const Eigen::VectorXd&) { callbacks = it.iteration; }, progress);
  EXPECT_TRUE(r.converged) << r.message;
  EXPECT_LT((r.x - Eigen::Vector2d(1, 1)).norm(), 1e-6);
  EXPECT_LT(r.iterations, 100);
  EXPECT_EQ(callbacks, r.iterations);
}

TEST(Bfgs, BacksAwayFromInfiniteValues)
{
  // A smooth cone centred at (1.5, 0), undefined (+∞, a failed simulation) beyond x = 2: its
  // curvature grows towards the centre, so quasi-Newton steps overshoot into the undefined region
  // and must be shortened.
  int infinite = 0;
  const Objective f = [&](const Eigen::VectorXd& x, Eigen::VectorXd& g) {
    if (x[0] > 2) {
      ++infinite;
      return HUGE_VAL;
    }
    const Eigen::Vector2d d = x - Eigen::Vector2d(1.5, 0);
    const double v = std::sqrt(1 + d.squaredNorm());
    g = d / v;
    return v;
  };
  NullProgress progress;
  BfgsOptions o;
  o.max_step = 100;
  o.relative_tolerance = 0;
  o.gradient_tolerance = 1e-8;
  const BfgsResult r = minimize_bfgs(f, Eigen::Vector2d(-30, 1), o, nullptr, progress);
  EXPECT_TRUE(r.converged) << r.message;
  EXPECT_GT(infinite, 0) << "the test should reach the undefined region";
  EXPECT_LT((r.x - Eigen::Vector2d(1.5, 0)).norm(), 1e-5);
}

TEST(Bfgs, RefusesAnInfiniteStart)
{
  const Objective f = [](const Eigen::VectorXd&, Eigen::VectorXd&) { return HUGE_VAL; };
  NullProgress progress;
  EXPECT_THROW(minimize_bfgs(f, Eigen::Vector2d(0, 0), {}, nullptr, progress), std::invalid_argument);
}

} // namespace
} // namespace fibermold
