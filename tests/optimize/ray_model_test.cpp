// The ray model of ray_model.hpp: on f = ½|x − (2, 0)|² + r, r = −log(1 − x₁) (+∞ for x₁ ≥ 1), whose
// quadratic part is exact, m(α) is f along the ray, so the step chosen is f's own minimizer on it
// (a root of u² − 3u + 1 with u = x₁), short of the wall the quadratic model steps through.
#include <cmath>

#include <gtest/gtest.h>

#include "optimize/ray_model.hpp"

namespace fibermold {
namespace {

double wall(const Eigen::VectorXd& x) { return x[0] < 1 ? -std::log(1 - x[0]) : HUGE_VAL; }

double objective(const Eigen::VectorXd& x) { return 0.5 * (x - Eigen::Vector2d(2, 0)).squaredNorm() + wall(x); }

TEST(RayModel, StopsAtTheObjectivesMinimumOnTheRayShortOfTheWall)
{
  const Eigen::Vector2d x(0, 0);
  // At x: g = (x − (2, 0)) + (1/(1 − x₁), 0) = (−1, 0); M = I + diag(1/(1 − x₁)², 0) = diag(2, 1).
  const Eigen::Vector2d g(-1, 0);
  const Eigen::Matrix2d M = Eigen::Vector2d(2, 1).asDiagonal();
  // The step the quadratic model asks is −M⁻¹g = (0.5, 0); a step twice as long, as a small damping
  // gives where the model is flatter than f, ends on the wall.
  const Eigen::Vector2d delta(1, 0);
  const RayStep step = ray_step(wall, x, g, M, delta);
  const double u = (3 - std::sqrt(5.0)) / 2; // x₁ at f's minimum along the ray: 0.381966
  EXPECT_NEAR(step.alpha * delta[0], u, 2e-3);
  const double best = objective(x) - objective(Eigen::Vector2d(u, 0)); // 0.7886
  EXPECT_NEAR(step.predicted, best, 1e-5);
  EXPECT_EQ(objective(x + delta), HUGE_VAL);
}

TEST(RayModel, TakesTheWholeStepWhereThePartIsFlat)
{
  const Eigen::Vector2d x(-5, 0), g(-7, 0);
  const Eigen::Matrix2d M = Eigen::Matrix2d::Identity();
  const auto none = [](const Eigen::VectorXd&) { return 0.0; };
  const RayStep step = ray_step(none, x, g, M, Eigen::Vector2d(7, 0));
  EXPECT_EQ(step.alpha, 1);
  EXPECT_NEAR(step.predicted, 24.5, 1e-9);
}

TEST(RayModel, PredictsNoDecreaseOnARayThatClimbs)
{
  const Eigen::Vector2d x(0, 0), g(-1, 0);
  const Eigen::Matrix2d M = Eigen::Matrix2d::Identity();
  const RayStep step = ray_step(wall, x, g, M, Eigen::Vector2d(-1, 0)); // uphill
  EXPECT_LE(step.predicted, 0);
}

TEST(RayModel, TakesOutTheCurvatureTheModelHoldsNotTheTermsOwn)
{
  // f = ½|x − (2, 0)|² + r, r = −0.4 x₁² + 0.1 x₁⁴: concave at x = 0, where a model Hessian projected
  // to be positive semi-definite holds r's as 0, so M = I and δ = −M⁻¹g = (2, 0). Along the ray,
  // f(αδ) = 2(α − 1)² − 1.6α² + 1.6α⁴, least at α* = 0.806. Given r's expansion as M holds it (r₁ = 0,
  // r₂ = δᵀ0δ = 0), m is f along the ray, so the step is α* and the prediction f's own decrease.
  // From central differences of r (r₂ = −3.2), m keeps +1.6α², a curvature no term has, and stops
  // short at 0.62, predicting less than f gives (the gain ratios of 1.4–1.9 the twisting bar met).
  const auto r = [](const Eigen::VectorXd& x) { return -0.4 * x[0] * x[0] + 0.1 * std::pow(x[0], 4); };
  const auto f = [&](double alpha) { return 2 * (alpha - 1) * (alpha - 1) + r(Eigen::Vector2d(2 * alpha, 0)); };
  const Eigen::Vector2d x(0, 0), g(-2, 0), delta(2, 0);
  const Eigen::Matrix2d M = Eigen::Matrix2d::Identity();
  double lo = 0, hi = 1; // f'(α) = 0.8α + 6.4α³ − 4 rises: bisection for its root
  for (int k = 0; k < 60; ++k) {
    const double mid = (lo + hi) / 2;
    if (0.8 * mid + 6.4 * std::pow(mid, 3) - 4 < 0)
      lo = mid;
    else
      hi = mid;
  }
  const double best = lo;
  ASSERT_NEAR(best, 0.806, 1e-3);
  const RayStep given = ray_step(r, x, g, M, delta, 0.0, 0.0);
  EXPECT_NEAR(given.alpha, best, 2e-3);
  EXPECT_NEAR(given.predicted, f(0) - f(best), 1e-5);
  const RayStep differenced = ray_step(r, x, g, M, delta);
  EXPECT_NEAR(differenced.alpha, 0.62, 0.02);
  EXPECT_LT(differenced.predicted, f(0) - f(differenced.alpha) - 0.1);
}

} // namespace
} // namespace fibermold
