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

} // namespace
} // namespace fibermold
