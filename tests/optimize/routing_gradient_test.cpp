// The gradient of the whole objective of eq. 4 (distance through equilibrium for two targets,
// curvature, skin barrier, pressure barrier, clearance barrier between the fibers) against central
// finite differences of the objective itself: relative error ≤ 1e-5 for control points, tangents
// and pressures. The parts of Levenberg-Marquardt's model against differences too: the forward
// sensitivities, and the regularizers' Hessian, which is measured one route at a time.
#include <cmath>
#include <random>

#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

#include "finite_differences.hpp"
#include "optimize/clearance_barrier.hpp"
#include "routing_fixture.hpp"

namespace fibermold {
namespace {

constexpr double kL = 0.04, kA = 0.012;

/// The bar of the fixture with one wavy muscle at 250 kPa: the target every test here has first.
Eigen::VectorXd wave_target(test::RoutingFixture& fx)
{
  return fx.actuated({{{0, 0.003, 0}, {0.02, 0.004, -0.003}, {kL, 0.003, 0}}}, {250e3});
}

/// Thin muscles (0.2 mm radius) kept 0.1 mm apart at least by a clearance barrier acting over 3 mm,
/// given to `problem` with weight 0.1: routes a few mm apart are within its reach.
struct ThinMuscleClearance {
  FiberClearance measure;
  ClearanceBarrier barrier;

  ThinMuscleClearance(const test::RoutingFixture& fx, const Routing& start, RoutingProblem& problem)
      : measure(*fx.skin, start.routes, 0.2e-3, 0.1e-3, 4000), barrier(measure, start.routes, 0.1e-3, 3e-3)
  {
    problem.set_clearance_barrier(&barrier, 0.1);
  }
};

TEST(RoutingProblem, GradientMatchesFiniteDifferencesAtRandomDesigns)
{
  test::RoutingFixture fx(kL, kA, 0.004, 12, 0.1, 1e-11);
  std::vector<Eigen::VectorXd> targets{
      wave_target(fx), fx.actuated({{{0, 0, -0.003}, {0.013, 0.003, 0}, {0.026, 0, 0.003}, {kL, -0.003, 0}}}, {300e3})};
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> jitter(-0.001, 0.001);
  const auto wiggle = [&](Eigen::Vector3d p) {
    return Eigen::Vector3d(p.x(), p.y() + jitter(rng), p.z() + jitter(rng));
  };
  Routing start;
  // Fiber a passes 2 mm from the skin (y = 4 mm of 6): the skin barrier (from 1 mm, over 1.5 mm) is active.
  start.routes = {
      test::RoutingFixture::route(
          "a", {{0, 0.001, 0}, wiggle({0.014, 0.004, 0.001}), wiggle({0.027, -0.002, 0.002}), {kL, 0.001, 0}}),
      test::RoutingFixture::route("b", {{0, -0.002, -0.001}, wiggle({0.02, -0.001, 0.002}), {kL, -0.002, 0.001}})};
  for (Route& r : start.routes)
    for (Eigen::Vector3d& t : r.tangents) t += Eigen::Vector3d(0, jitter(rng), jitter(rng));
  start.pressures.resize(2, 2);
  start.pressures << 180e3, 418e3, // 418 kPa: within 2 % of the 425 kPa bound, the barrier acts
      90e3, 240e3;
  RoutingSettings settings;
  settings.weight_curvature = 1e-3;
  settings.skin_distance = 1e-3;
  settings.skin_band = 1.5e-3;
  RoutingProblem problem(*fx.sim, fx.model, *fx.skin, targets, fx.curves, start, settings);
  const ThinMuscleClearance clearance(fx, start, problem); // a and b, a few mm apart, within its reach

  const Eigen::VectorXd z = problem.variables(start);
  Eigen::VectorXd analytic;
  RoutingTerms terms;
  const double f0 = problem.evaluate(z, &analytic, &terms);
  ASSERT_TRUE(std::isfinite(f0));
  EXPECT_GT(terms.per_target[0], 0);
  EXPECT_GT(terms.per_target[1], 0);
  EXPECT_GT(terms.curvature, 0);
  EXPECT_GT(terms.skin, 0) << "the skin barrier should be active";
  EXPECT_GT(terms.pressure, 0) << "the pressure barrier should be active";
  EXPECT_GT(terms.clearance, 0) << "the clearance barrier should be active";

  // Variables in mm and 10 kPa: a step of 1e-3 is 1 µm or 10 Pa. Each difference is taken
  // through equilibria solved to their tolerance: 1e-5 of the largest entry.
  const test::ScalarFunction f = [&](const Eigen::VectorXd& v) { return problem.evaluate(v); };
  const Eigen::VectorXd fd = test::fd_gradient(f, z, 1e-3);
  const Eigen::Index np = 4; // the last four variables are the pressures
  const Eigen::Index nr = z.size() - np;
  const double routing_error = (fd.head(nr) - analytic.head(nr)).norm() / analytic.head(nr).norm();
  const double pressure_error = (fd.tail(np) - analytic.tail(np)).norm() / analytic.tail(np).norm();
  std::printf("routing problem gradient: relative error %.2e (routing, %ld values), %.2e (pressures)\n", routing_error,
              static_cast<long>(nr), pressure_error);
  EXPECT_TRUE(test::matches_fd(analytic.head(nr), fd.head(nr), 1e-5));
  EXPECT_TRUE(test::matches_fd(analytic.tail(np), fd.tail(np), 1e-5));

  // The regularizers' part, Levenberg-Marquardt's exact part: its gradient against differences of
  // its values, and the same derivatives whether computed afresh or kept from evaluate's model.
  Eigen::VectorXd exact_gradient, kept_gradient;
  Eigen::MatrixXd exact_hessian, kept_hessian, model;
  problem.regularizer_derivatives(z, exact_gradient, exact_hessian);
  const test::ScalarFunction r = [&](const Eigen::VectorXd& v) { return problem.regularizer_value(v); };
  EXPECT_TRUE(test::matches_fd(exact_gradient, test::fd_gradient(r, z, 1e-3), 1e-5));
  ASSERT_TRUE(std::isfinite(problem.evaluate(z, &analytic, nullptr, &model)));
  problem.regularizer_derivatives(z, kept_gradient, kept_hessian);
  EXPECT_EQ(kept_gradient, exact_gradient);
  EXPECT_EQ(kept_hessian, exact_hessian);
}

TEST(RoutingProblem, RegularizerHessianOfThreeFibersMatchesDifferencesOfTheWholeGradient)
{
  // regularizer_hessian measures a column by moving one route and differencing only that route's
  // terms and the clearance pairs that include it. With three fibers, each pair within the
  // clearance barrier's reach, that must equal central differences of the whole regularizer
  // gradient (every term, every pair), both projected to be positive semi-definite the same way.
  test::RoutingFixture fx(kL, kA, 0.004, 12, 0.1, 1e-11);
  const std::vector<Eigen::VectorXd> targets{wave_target(fx)};
  Routing start;
  start.routes = {
      test::RoutingFixture::route("a",
                                  {{0, 0.0012, 0}, {0.015, 0.0015, 0.0005}, {0.028, 0.0012, -0.0005}, {kL, 0.0012, 0}}),
      test::RoutingFixture::route("b", {{0, -0.001, 0.0015}, {0.02, -0.0005, 0.001}, {kL, -0.001, 0.0015}}),
      test::RoutingFixture::route("c", {{0, -0.001, -0.0015}, {0.02, -0.0015, -0.001}, {kL, -0.001, -0.0015}})};
  start.pressures = Eigen::MatrixXd::Constant(1, 3, 200e3);
  RoutingSettings settings;
  settings.weight_curvature = 1e-3;
  RoutingProblem problem(*fx.sim, fx.model, *fx.skin, targets, fx.curves, start, settings);
  const ThinMuscleClearance clearance(fx, start, problem);

  const Eigen::VectorXd z = problem.variables(start);
  const Eigen::MatrixXd model = problem.regularizer_hessian(z);
  const auto whole_gradient = [&](const Eigen::VectorXd& at) {
    Eigen::VectorXd g;
    Eigen::MatrixXd unused;
    problem.regularizer_derivatives(at, g, unused);
    return g;
  };
  Eigen::MatrixXd fd(z.size(), z.size());
  for (Eigen::Index i = 0; i < z.size(); ++i) {
    const double h = 1e-5; // 10 nm, or 0.1 Pa
    Eigen::VectorXd up = z, down = z;
    up[i] += h;
    down[i] -= h;
    fd.col(i) = (whole_gradient(up) - whole_gradient(down)) / (2 * h);
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen((fd + fd.transpose()) / 2);
  const Eigen::MatrixXd projected =
      eigen.eigenvectors() * eigen.eigenvalues().cwiseMax(0).asDiagonal() * eigen.eigenvectors().transpose();
  const double error = (model - projected).norm() / projected.norm();
  std::printf("regularizer Hessian, three fibers: relative error %.2e over %ld variables\n", error,
              static_cast<long>(z.size()));
  EXPECT_LT(error, 1e-5);
  // Each pair couples its two fibers (2.3-3 mm apart, within the barrier's 3.1 mm): the block of
  // their variables is measured, and the model's equals the differences' (a filter that kept only
  // the pairs whose first fiber moves would halve the blocks of the pairs it measures once).
  // A fiber's variables: its inner points' and all its tangents' components (its ends stay fixed).
  const Eigen::Index na = (2 + 4) * 3, nb = (1 + 3) * 3;
  ASSERT_EQ(z.size(), na + 2 * nb + 3);
  const Eigen::Index offset[3] = {0, na, na + nb}, count[3] = {na, nb, nb};
  for (const auto& [f, g] : {std::pair{0, 1}, std::pair{0, 2}, std::pair{1, 2}}) {
    const double raw = fd.block(offset[f], offset[g], count[f], count[g]).norm();
    const double measured = model.block(offset[f], offset[g], count[f], count[g]).norm();
    const double differences = projected.block(offset[f], offset[g], count[f], count[g]).norm();
    std::printf("fibers %c-%c: block %.3e (differences %.3e, before the projection %.3e)\n", 'a' + f, 'a' + g, measured,
                differences, raw);
    EXPECT_GT(raw, 1e-3 * fd.norm()) << "fibers " << f << " and " << g << " should be within the barrier's reach";
    EXPECT_NEAR(measured, differences, 1e-4 * differences);
  }
}

TEST(RoutingProblem, SensitivitiesAndModelHessianMatchFiniteDifferences)
{
  // The forward sensitivities dx/dz of Levenberg-Marquardt's model against central differences of
  // the equilibria, and its Gauss-Newton Hessian Σ SᵀQS against the one built from those differences.
  test::RoutingFixture fx(kL, kA, 0.004, 12, 0.1, 1e-11);
  const std::vector<Eigen::VectorXd> targets{wave_target(fx)};
  Routing start;
  start.routes = {
      test::RoutingFixture::route("a", {{0, 0.001, 0}, {0.014, 0.003, 0.001}, {0.027, -0.002, 0.002}, {kL, 0.001, 0}})};
  start.pressures = Eigen::MatrixXd::Constant(1, 1, 180e3);
  RoutingProblem problem(*fx.sim, fx.model, *fx.skin, targets, fx.curves, start, {});
  const Eigen::VectorXd z = problem.variables(start);
  Eigen::VectorXd g;
  Eigen::MatrixXd model;
  ASSERT_TRUE(std::isfinite(problem.evaluate(z, &g, nullptr, &model)));
  const Eigen::VectorXd x = problem.equilibrium(start, 0);
  const Eigen::MatrixXd S = problem.sensitivities(start, 0, x);
  ASSERT_EQ(S.cols(), z.size());
  Eigen::MatrixXd fd(x.size(), z.size());
  for (Eigen::Index i = 0; i < z.size(); ++i) {
    const double h = 1e-3; // 1 µm or 10 Pa
    Eigen::VectorXd up = z, down = z;
    up[i] += h;
    down[i] -= h;
    fd.col(i) = (problem.equilibrium(problem.routing(up), 0) - problem.equilibrium(problem.routing(down), 0)) / (2 * h);
  }
  const double error = (S - fd).norm() / fd.norm();
  std::printf("sensitivities dx/dz: relative error %.2e over %ld columns\n", error, static_cast<long>(z.size()));
  // Not exact: each column is a back-substitution with the factorization the solve ended on, of
  // the Hessian a step before x (newton_solver.hpp); 1.0e-3 on this bar. A wrong derivative is O(1) off.
  EXPECT_LT(error, 3e-3);
  EXPECT_GT(fd.norm(), 0);
  // The model's distance part from the differences: Σ_j w SᵀNᵀN S, as DistanceObjective builds it.
  const Eigen::MatrixXd gn = problem.distance(0).gauss_newton_hessian(fd);
  const Eigen::MatrixXd regularizers = problem.regularizer_hessian(z);
  const double model_error = (model - regularizers - gn).norm() / gn.norm();
  std::printf("Gauss-Newton Hessian: relative error %.2e\n", model_error);
  EXPECT_LT(model_error, 6e-3); // 1.8e-3: twice the sensitivities' error
}

} // namespace
} // namespace fibermold
