// BFGS with LBFGSpp's line search: the Rosenbrock valley to 1e-6, a wall of +∞ (a failed
// simulation) that the line search backs away from, and a jump up (a snap) it stops at.
#include <cmath>
#include <cstdio>

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
  MinimizerOptions o;
  o.gradient_tolerance = 1e-8;
  o.relative_tolerance = 0;
  int callbacks = 0;
  const MinimizerResult r = minimize_bfgs(
      rosenbrock, Eigen::Vector2d(-1.2, 1), o,
      [&](const MinimizerIteration& it, const Eigen::VectorXd&) { callbacks = it.iteration; }, progress);
  EXPECT_TRUE(r.converged()) << r.message;
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
  MinimizerOptions o;
  o.max_step = 100;
  o.relative_tolerance = 0;
  o.gradient_tolerance = 1e-8;
  const MinimizerResult r = minimize_bfgs(f, Eigen::Vector2d(-30, 1), o, nullptr, progress);
  EXPECT_TRUE(r.converged()) << r.message;
  EXPECT_GT(infinite, 0) << "the test should reach the undefined region";
  EXPECT_LT((r.x - Eigen::Vector2d(1.5, 0)).norm(), 1e-5);
}

TEST(Bfgs, StopsWhereTheObjectiveJumpsUpJustAhead)
{
  // A slope down to x = 1, where f jumps up by 10 (a body that snaps to another equilibrium
  // there): the best design sits at the jump. Each line search finds a little less short of it
  // and spends all its 20 evaluations (Wolfe's extensions cross the jump); the run stops at the
  // first that gains almost nothing: 101 evaluations, where it took 161 before that rule.
  int evaluations = 0;
  const Objective f = [&](const Eigen::VectorXd& x, Eigen::VectorXd& g) {
    ++evaluations;
    g = Eigen::Vector2d(-1, 2 * x[1]);
    return 10 - x[0] + x[1] * x[1] + (x[0] > 1 ? 10.0 : 0.0);
  };
  NullProgress progress;
  MinimizerOptions o;
  o.max_iterations = 1000;
  const MinimizerResult r = minimize_bfgs(f, Eigen::Vector2d(-1, 0), o, nullptr, progress);
  EXPECT_EQ(r.termination, Termination::line_search) << r.message;
  EXPECT_FALSE(r.converged());
  EXPECT_NE(r.message.find("used all 20 evaluations"), std::string::npos) << r.message;
  EXPECT_NEAR(r.x[0], 1.0, 1e-3);
  std::printf("%d evaluations: %s\n", evaluations, r.message.c_str());
  EXPECT_LE(evaluations, 121);
}

TEST(Bfgs, SaysWhyItStoppedAndCallsOnlyAVanishingGradientConverged)
{
  NullProgress progress;
  MinimizerOptions o;
  o.gradient_tolerance = 1e-12;
  o.relative_tolerance = 1e6; // any fall over 10 iterations counts as stalling: met at iteration 11
  const MinimizerResult stalled = minimize_bfgs(rosenbrock, Eigen::Vector2d(-1.2, 1), o, nullptr, progress);
  EXPECT_EQ(stalled.termination, Termination::stalled) << stalled.message;
  EXPECT_FALSE(stalled.converged());
  EXPECT_EQ(choice_name(stalled.termination), "stalled");
  o.relative_tolerance = 0;
  o.max_iterations = 3;
  const MinimizerResult limited = minimize_bfgs(rosenbrock, Eigen::Vector2d(-1.2, 1), o, nullptr, progress);
  EXPECT_EQ(limited.termination, Termination::iteration_limit) << limited.message;
  EXPECT_EQ(limited.iterations, 3);
  EXPECT_FALSE(limited.converged());
}

TEST(Bfgs, RefusesAnInfiniteStart)
{
  const Objective f = [](const Eigen::VectorXd&, Eigen::VectorXd&) { return HUGE_VAL; };
  NullProgress progress;
  EXPECT_THROW(minimize_bfgs(f, Eigen::Vector2d(0, 0), {}, nullptr, progress), std::invalid_argument);
}

} // namespace
} // namespace fibermold
