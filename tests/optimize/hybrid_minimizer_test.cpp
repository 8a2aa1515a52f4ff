// The hybrid minimizer hands over from BFGS to Levenberg-Marquardt where BFGS slows down: on the
// Rosenbrock valley as least squares, a BFGS run started on the valley's floor at (0.8, 0.64) and
// told to hand over early (f falling by less than 30 % over two iterations) is carried on to the
// minimum, (1, 1) within 1e-6, and converges;
// iterations are numbered on across the switch; a run BFGS finishes itself is BFGS's alone.
#include <gtest/gtest.h>

#include "optimize/hybrid_minimizer.hpp"
#include "rosenbrock.hpp"

namespace fibermold {
namespace {

using test::rosenbrock;
using test::rosenbrock_value;

TEST(HybridMinimizer, LevenbergMarquardtCarriesAStalledBfgsRunToTheMinimum)
{
  NullProgress progress;
  MinimizerOptions o;
  o.window = 2;
  o.switch_tolerance = 0.3; // BFGS hands over where two steps gain less than 30 % of f
  o.relative_tolerance = 0.3;
  o.gradient_tolerance = 0;
  o.decrease_tolerance = 1e-14;
  std::vector<int> numbers;
  const MinimizerResult r = minimize_hybrid(
      rosenbrock_value, rosenbrock, Eigen::Vector2d(0.8, 0.64), o,
      [&](const MinimizerIteration& it, const Eigen::VectorXd&) { numbers.push_back(it.iteration); }, progress);
  EXPECT_TRUE(r.converged()) << r.message;
  EXPECT_LT((r.x - Eigen::Vector2d(1, 1)).norm(), 1e-6) << r.message;
  EXPECT_EQ(r.message.rfind("BFGS stalled after ", 0), 0u) << r.message;
  ASSERT_EQ(static_cast<int>(numbers.size()), r.iterations);
  for (int k = 0; k < r.iterations; ++k) EXPECT_EQ(numbers[k], k + 1);
}

TEST(HybridMinimizer, ARunBfgsFinishesIsBfgsAlone)
{
  NullProgress progress;
  MinimizerOptions o;
  o.relative_tolerance = 0;
  o.switch_tolerance = 0;
  o.gradient_tolerance = 1e-8;
  int model_calls = 0;
  const ModelObjective counted = [&](const Eigen::VectorXd& x, Eigen::VectorXd& g, Eigen::MatrixXd& B) {
    ++model_calls;
    return rosenbrock(x, g, B);
  };
  const MinimizerResult r = minimize_hybrid(rosenbrock_value, counted, Eigen::Vector2d(-1.2, 1), o, nullptr, progress);
  EXPECT_EQ(r.termination, Termination::gradient_tolerance) << r.message;
  EXPECT_EQ(model_calls, 0);
  EXPECT_LT((r.x - Eigen::Vector2d(1, 1)).norm(), 1e-6);
}

} // namespace
} // namespace fibermold
