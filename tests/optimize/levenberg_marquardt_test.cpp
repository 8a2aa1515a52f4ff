// Levenberg-Marquardt on a Gauss-Newton model: the Rosenbrock valley as the least-squares problem
// r = (10(x₂ − x₁²), 1 − x₁), which converges by the model's decrease (a first-order criterion,
// not a stall) with |x − (1, 1)| ≤ 1e-6; a region of +∞ in the way; and a model that cannot
// reach the minimum (a barrier the objective has and the model lacks) ends by its rejections, or,
// with the stall rule on, stalls;
// a barrier whose exact values the minimizer is given (ray_model.hpp) is approached, not hit, and
// with its derivatives given the secant term learns nothing of it.
#include <cmath>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "optimize/levenberg_marquardt.hpp"
#include "rosenbrock.hpp"

namespace fibermold {
namespace {

using test::rosenbrock;

/// Options under which a run ends only by converging (the model's decrease at most `decrease` of f),
/// by its rejections or at the iteration limit: no gradient or stall rule.
MinimizerOptions run_to_convergence(double decrease)
{
  MinimizerOptions o;
  o.relative_tolerance = 0;
  o.gradient_tolerance = 0;
  o.decrease_tolerance = decrease;
  return o;
}

TEST(LevenbergMarquardt, ConvergesOnTheRosenbrockValleyByTheModelsDecrease)
{
  NullProgress progress;
  const MinimizerOptions o = run_to_convergence(1e-14);
  int callbacks = 0;
  const MinimizerResult r = minimize_levenberg_marquardt(
      rosenbrock, Eigen::Vector2d(-1.2, 1), o,
      [&](const MinimizerIteration& it, const Eigen::VectorXd&) { callbacks = it.iteration; }, progress);
  EXPECT_TRUE(r.converged()) << r.message; // by the model's decrease, or at a zero gradient
  EXPECT_LT((r.x - Eigen::Vector2d(1, 1)).norm(), 1e-6);
  EXPECT_LT(r.iterations, 40); // BFGS takes 30–40 on it; a zero-residual problem is Gauss-Newton's best case
  EXPECT_EQ(callbacks, r.iterations);
}

/// Dennis & Schnabel's large-residual problem (Numerical Methods for Unconstrained Optimization,
/// Example 10.2.5): r = (x + 1, λx² + x − 1), minimum at x = 0 with r = (1, −1) for λ < 1. There
/// f'' = 2 − 2λ while Gauss-Newton's JᵀJ = 2: with λ = 0.9 the model is 10× too stiff, so
/// Gauss-Newton closes only 10 % of the distance per step, and its decrease ½g²/JᵀJ claims 10×
/// too little is left.
double large_residual(const Eigen::VectorXd& x, Eigen::VectorXd& g, Eigen::MatrixXd& B)
{
  constexpr double lambda = 0.9;
  const Eigen::Vector2d r(x[0] + 1, lambda * x[0] * x[0] + x[0] - 1);
  const Eigen::Vector2d J(1, 2 * lambda * x[0] + 1);
  g = Eigen::VectorXd::Constant(1, J.dot(r));
  B = Eigen::MatrixXd::Constant(1, 1, J.squaredNorm());
  return 0.5 * r.squaredNorm();
}

TEST(LevenbergMarquardt, LearnsWhatTheGaussNewtonModelLeavesOutOnALargeResidual)
{
  NullProgress progress;
  const MinimizerOptions o = run_to_convergence(1e-12);
  const MinimizerResult r =
      minimize_levenberg_marquardt(large_residual, Eigen::VectorXd::Constant(1, 1.0), o, nullptr, progress);
  EXPECT_TRUE(r.converged()) << r.message;
  // Gauss-Newton alone: 0.9 of the distance kept per step, about 100 steps to 1e-5, and its
  // decrease test would pass at |x| ≈ 1e-5 × √10.
  EXPECT_LT(std::abs(r.x[0]), 1e-5);
  EXPECT_LT(r.iterations, 25);
}

TEST(LevenbergMarquardt, ASlowButFaithfulModelIsNotAStall)
{
  // f = |x|³/3 + 1000 with its exact Hessian 2|x|: Newton halves x per step, so each step gains a
  // tiny share of f (under 1e-3 once |x| < 1.5) while the model predicts as little as is left.
  // The run goes on to converge where a stall rule on f alone would have ended it near x = 1.5.
  const ModelObjective f = [](const Eigen::VectorXd& x, Eigen::VectorXd& g, Eigen::MatrixXd& B) {
    const double a = std::abs(x[0]);
    g = Eigen::VectorXd::Constant(1, x[0] * a);
    B = Eigen::MatrixXd::Constant(1, 1, 2 * a);
    return a * a * a / 3 + 1000;
  };
  NullProgress progress;
  MinimizerOptions o;
  o.window = 1;
  o.relative_tolerance = 1e-3;
  o.gradient_tolerance = 0;
  o.decrease_tolerance = 1e-9;
  o.max_step = 100;
  const MinimizerResult r = minimize_levenberg_marquardt(f, Eigen::VectorXd::Constant(1, 10.0), o, nullptr, progress);
  EXPECT_EQ(r.termination, Termination::decrease_tolerance) << r.message;
  EXPECT_LT(std::abs(r.x[0]), 0.02);
}

/// f = ½|x − (2, 0)|², +∞ for x₁ > 1, with the model B = I, which does not know the wall.
double behind_a_wall(const Eigen::VectorXd& x, Eigen::VectorXd& g, Eigen::MatrixXd& B)
{
  if (x[0] > 1) return HUGE_VAL;
  g = x - Eigen::Vector2d(2, 0);
  B = Eigen::Matrix2d::Identity();
  return 0.5 * g.squaredNorm();
}

TEST(LevenbergMarquardt, AModelThatKeepsPredictingWhatItDoesNotDeliverStalls)
{
  // f = ½|x − (2, 0)|², +∞ for x₁ > 1, as below, with the stall rule on (minimizer.hpp's
  // model_stall_message): against the wall (f ≈ 0.625) the model predicts all of f left after
  // every iteration, while the steps it is allowed gain less and less. That is a stall, named so,
  // at the best point found, before the rejections would end the run.
  NullProgress progress;
  MinimizerOptions o;
  o.window = 3;
  o.relative_tolerance = 1e-3;
  std::vector<double> predicted, values;
  const MinimizerResult r = minimize_levenberg_marquardt(
      behind_a_wall, Eigen::Vector2d(0, 1), o,
      [&](const MinimizerIteration& it, const Eigen::VectorXd&) {
        predicted.push_back(it.predicted_decrease);
        values.push_back(it.value);
      },
      progress);
  EXPECT_EQ(r.termination, Termination::stalled) << r.message;
  EXPECT_LE(r.x[0], 1);
  EXPECT_GT(r.x[0], 0.9);
  ASSERT_GE(predicted.size(), 3u);
  for (std::size_t i = predicted.size() - 3; i < predicted.size(); ++i)
    EXPECT_GT(predicted[i], 0.9 * values[i]); // all of f (it is ½|g|²), far above the window's 1e-3
}

TEST(LevenbergMarquardt, RejectsStepsIntoInfiniteValuesAndStillConverges)
{
  // The same valley, undefined (+∞, a failed simulation) below x₂ = −1: from (−1.2, 1) the
  // Gauss-Newton step lands at (1, −3.84); it is rejected, μ grows, and the run goes round.
  int infinite = 0;
  const ModelObjective f = [&](const Eigen::VectorXd& x, Eigen::VectorXd& g, Eigen::MatrixXd& B) {
    if (x[1] < -1) {
      ++infinite;
      return HUGE_VAL;
    }
    return rosenbrock(x, g, B);
  };
  NullProgress progress;
  MinimizerOptions o;
  o.max_step = 100;
  o.relative_tolerance = 0;
  o.gradient_tolerance = 0;
  o.decrease_tolerance = 1e-14;
  const MinimizerResult r = minimize_levenberg_marquardt(f, Eigen::Vector2d(-1.2, 1), o, nullptr, progress);
  EXPECT_TRUE(r.converged()) << r.message;
  EXPECT_GT(infinite, 0) << "the test should reach the undefined region";
  EXPECT_LT((r.x - Eigen::Vector2d(1, 1)).norm(), 1e-6);
}

TEST(LevenbergMarquardt, AWallTheModelDoesNotKnowEndsTheRunAtTheBestPointNotConverged)
{
  // f = ½|x − (2, 0)|², +∞ for x₁ > 1: the model keeps pointing into the wall, so steps shrink
  // until max_line_search of them in a row are rejected. (The routing problem meets this where a
  // fiber's end, unguarded by the skin barrier, reaches the skin: docs/optimize.md.)
  NullProgress progress;
  MinimizerOptions o;
  o.relative_tolerance = 0;
  const MinimizerResult r = minimize_levenberg_marquardt(behind_a_wall, Eigen::Vector2d(0, 1), o, nullptr, progress);
  EXPECT_FALSE(r.converged());
  EXPECT_EQ(r.termination, Termination::line_search) << r.message;
  EXPECT_LE(r.x[0], 1);
  EXPECT_GT(r.x[0], 0.99);
  EXPECT_LT(r.value, 2.5); // f at the start
  // The message gives the last trial's length, which says how close to the wall it stopped (not the
  // damping, which doubling takes to 1e68 and which says nothing to a user).
  const std::string said =
      fmt::format("{} trial steps in a row did not lower f, the last moving no variable more than ", o.max_line_search);
  ASSERT_EQ(r.message.rfind(said, 0), 0u) << r.message;
  const double last = std::stod(r.message.substr(said.size()));
  EXPECT_GT(last, 0);
  EXPECT_LT(last, 1e-12); // pressed against the wall, the trials shrank to nothing (6.1e-72 here)
  EXPECT_THAT(r.message, ::testing::HasSubstr("(mm, or 10 kPa)"));
}

/// f = ½|x − (2, 0)|² − c log(1 − x₁) (+∞ for x₁ ≥ 1), c = 0.01: a minimum held by a log
/// barrier, at x₁ = (3 − √1.04)/2 = 0.990098, as a route is held by its bend-radius or skin barrier.
/// The model holds the barrier's Hessian at x, which is flat far from the wall.
constexpr double kBarrierWeight = 0.01;
double barrier_part(const Eigen::VectorXd& x) { return x[0] < 1 ? -kBarrierWeight * std::log(1 - x[0]) : HUGE_VAL; }
/// Its gradient and Hessian, which the model below holds exactly.
void barrier_derivatives(const Eigen::VectorXd& x, Eigen::VectorXd& g, Eigen::MatrixXd& H)
{
  const double w = 1 - x[0];
  g = Eigen::Vector2d(kBarrierWeight / w, 0);
  H = Eigen::Matrix2d::Zero();
  H(0, 0) = kBarrierWeight / (w * w);
}

TEST(LevenbergMarquardt, ABarriersExactValuesKeepItsStepsShortOfTheWall)
{
  int infinite = 0, evaluations = 0;
  const ModelObjective f = [&](const Eigen::VectorXd& x, Eigen::VectorXd& g, Eigen::MatrixXd& B) {
    ++evaluations;
    if (x[0] >= 1) {
      ++infinite;
      return HUGE_VAL;
    }
    const double w = 1 - x[0];
    g = x - Eigen::Vector2d(2, 0);
    g[0] += kBarrierWeight / w;
    B = Eigen::Matrix2d::Identity();
    B(0, 0) += kBarrierWeight / (w * w);
    return 0.5 * (x - Eigen::Vector2d(2, 0)).squaredNorm() + barrier_part(x);
  };
  NullProgress progress;
  const MinimizerOptions o = run_to_convergence(1e-12);
  const MinimizerResult blind = minimize_levenberg_marquardt(f, Eigen::Vector2d(0, 1), o, nullptr, progress);
  const int blind_infinite = std::exchange(infinite, 0), blind_evaluations = std::exchange(evaluations, 0);
  const MinimizerResult seeing =
      minimize_levenberg_marquardt(f, Eigen::Vector2d(0, 1), o, nullptr, progress, {barrier_part, barrier_derivatives});
  const double minimum = (3 - std::sqrt(1.04)) / 2;
  EXPECT_TRUE(seeing.converged()) << seeing.message;
  EXPECT_NEAR(seeing.x[0], minimum, 1e-7);
  EXPECT_NEAR(seeing.x[1], 0, 1e-7);
  EXPECT_EQ(infinite, 0) << "a step past the wall, which the ray model sees";
  EXPECT_GT(blind_infinite, 0) << "the test should lead the quadratic model into the wall";
  EXPECT_LT(evaluations, blind_evaluations);
  RecordProperty("evaluations", evaluations);
  RecordProperty("evaluations_without_the_exact_part", blind_evaluations);
  EXPECT_TRUE(blind.converged() || blind.termination == Termination::line_search) << blind.message;

  // With the barrier's values but not its derivatives, the secant term learns the change of the
  // barrier's curvature along each step, which B already holds, and overstates it.
  const int seeing_evaluations = std::exchange(evaluations, 0);
  const MinimizerResult valued =
      minimize_levenberg_marquardt(f, Eigen::Vector2d(0, 1), o, nullptr, progress, {barrier_part, {}});
  EXPECT_TRUE(valued.converged()) << valued.message;
  EXPECT_LT(seeing_evaluations, evaluations);
  RecordProperty("evaluations_with_the_exact_values_alone", evaluations);
}

TEST(LevenbergMarquardt, AnIndefiniteModelStepsDownhillByItsEigenvaluesMagnitudes)
{
  // f = Σ (¼xᵢ⁴ − ½xᵢ²) + 1 with its exact Hessian diag(3xᵢ² − 1): indefinite at the start (0.05, 3),
  // where the first variable sits near the top of its hump. The model takes the magnitudes of its
  // eigenvalues (saddle-free Newton), so the step leaves the hump downhill, and both variables
  // reach their minima at 1 in a few steps.
  const ModelObjective f = [](const Eigen::VectorXd& x, Eigen::VectorXd& g, Eigen::MatrixXd& B) {
    g = x.array().cube() - x.array();
    B = (3 * x.array().square() - 1).matrix().asDiagonal();
    return (0.25 * x.array().pow(4) - 0.5 * x.array().square()).sum() + 1;
  };
  NullProgress progress;
  const MinimizerOptions o = run_to_convergence(1e-14);
  const MinimizerResult r = minimize_levenberg_marquardt(f, Eigen::Vector2d(0.05, 3), o, nullptr, progress);
  EXPECT_TRUE(r.converged()) << r.message;
  EXPECT_NEAR(r.x[0], 1, 1e-6);
  EXPECT_NEAR(r.x[1], 1, 1e-6);
  EXPECT_LE(r.iterations, 12);
  RecordProperty("iterations", r.iterations);
}

TEST(LevenbergMarquardt, ThrowsWhenTheStartIsNotFinite)
{
  NullProgress progress;
  const ModelObjective f = [](const Eigen::VectorXd&, Eigen::VectorXd&, Eigen::MatrixXd&) { return HUGE_VAL; };
  EXPECT_THROW(minimize_levenberg_marquardt(f, Eigen::Vector2d(0, 0), {}, nullptr, progress), std::invalid_argument);
}

} // namespace
} // namespace fibermold
