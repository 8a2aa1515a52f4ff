// The gradient of the distance to a target through equilibrium (adjoint, eq. 9) against central
// finite differences that re-solve the equilibrium: relative error ≤ 1e-5 for control points,
// tangents and pressure; a target's weight scales the distance, its gradient and its model.
#include <cmath>

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <gtest/gtest.h>

#include "../sim/sim_fixtures.hpp"
#include "finite_differences.hpp"
#include "optimize/adjoint_gradient.hpp"
#include "optimize/distance_objective.hpp"
#include "sim/external_forces.hpp"

namespace fibermold {
namespace {

constexpr double kL = 0.04, kA = 0.012;

struct Problem {
  TetMesh mesh = test::box_mesh({0, -kA / 2, -kA / 2}, {kL, kA / 2, kA / 2}, 0.004);
  MuscleModel model;
  std::vector<TrackingSamples> curves{sample_tracking_curve({{0, 0, 0}, {kL, 0, 0}}, 12, 1.0, 0.1)};
  Eigen::VectorXd target;
  Eigen::VectorXd warm;

  SimulationOptions options() const
  {
    SimulationOptions o;
    o.gravity = {0, 0, -9.81};
    o.fixed_nodes = {nodes_in_box(mesh.nodes, {-1, -1, -1}, {1e-9, 1, 1})};
    o.newton.tolerance = 1e-11;
    return o;
  }

  /// Equilibrium with one fiber; returns f_dist and, when asked, its adjoint gradient.
  double evaluate(const std::vector<Eigen::Vector3d>& points, const std::vector<Eigen::Vector3d>& tangents, double p,
                  FiberParameterGradient* gradient = nullptr)
  {
    Simulation sim(mesh, options());
    const HermiteSpline spline(points, tangents);
    auto muscle =
        std::make_unique<MuscleEnergy>(sim.basis(), model, spline, segment_parameters(HermiteSpline(points), 24), p);
    const MuscleEnergy* m = muscle.get();
    sim.add_energy(std::move(muscle));
    Eigen::VectorXd x = warm.size() ? warm : sim.rest();
    NullProgress progress;
    const NewtonSummary s = sim.solve(x, progress);
    EXPECT_TRUE(s.converged) << s.brief();
    const DistanceObjective f(sim.basis(), curves, target);
    if (gradient) *gradient = adjoint_gradient(sim, x, f.gradient(x), {m}).front();
    if (warm.size() == 0) warm = x;
    return f.value(x);
  }
};

TEST(AdjointGradient, MatchesFiniteDifferencesThroughEquilibrium)
{
  Problem pr;
  const std::vector<Eigen::Vector3d> points{
      {0, 0.001, 0}, {0.014, 0.003, 0.001}, {0.027, -0.002, 0.002}, {kL, 0.001, 0}};
  const std::vector<Eigen::Vector3d> tangents = HermiteSpline(points).tangents();
  // The target: the same body bent by a differently routed fiber.
  {
    Simulation sim(pr.mesh, pr.options());
    const HermiteSpline other({{0, 0.003, 0}, {0.02, 0.004, -0.003}, {kL, 0.003, 0}});
    sim.add_energy(std::make_unique<MuscleEnergy>(sim.basis(), pr.model, other, segment_parameters(other, 24), 250e3));
    pr.target = sim.rest();
    NullProgress progress;
    ASSERT_TRUE(sim.solve(pr.target, progress).converged);
  }
  const double p = 180e3;
  FiberParameterGradient analytic;
  const double f0 = pr.evaluate(points, tangents, p, &analytic);
  ASSERT_GT(f0, 0);

  // Central differences: interior points, all tangents, the pressure. Each difference is taken
  // through an equilibrium solved to its tolerance: 1e-5 of the largest entry.
  const std::size_t interior = points.size() - 2; // the end points stay fixed
  const test::ScalarFunction f = [&](const Eigen::VectorXd& v) {
    const auto lists = test::unstacked(v, {interior, tangents.size()});
    auto P = points;
    std::copy(lists[0].begin(), lists[0].end(), P.begin() + 1);
    return pr.evaluate(P, lists[1], p);
  };
  const std::vector<Eigen::Vector3d> inner(points.begin() + 1, points.end() - 1),
      inner_analytic(analytic.points.begin() + 1, analytic.points.end() - 1);
  const Eigen::VectorXd AN = test::stacked({inner_analytic, analytic.tangents});
  const Eigen::VectorXd FD = test::fd_gradient(f, test::stacked({inner, tangents}), 1e-6);
  const test::ScalarFunction in_pressure = [&](const Eigen::VectorXd& q) {
    return pr.evaluate(points, tangents, q[0]);
  };
  const double FD_p =
      test::central_difference(in_pressure, Eigen::VectorXd::Constant(1, p), Eigen::VectorXd::Ones(1), 10.0);
  ASSERT_GT(AN.norm(), 0);
  std::printf("adjoint gradient: relative error %.2e (routing, %ld values), %.2e (pressure)\n",
              (FD - AN).norm() / AN.norm(), static_cast<long>(AN.size()),
              std::abs(FD_p - analytic.pressure) / std::abs(analytic.pressure));
  EXPECT_TRUE(test::matches_fd(AN, FD, 1e-5));
  EXPECT_TRUE(test::matches_fd(analytic.pressure, FD_p, 1e-5));
}

TEST(TrackingCurve, SamplesEquallySpacedWithOrthonormalFrames)
{
  const TrackingSamples s = sample_tracking_curve({{0, 0, 0}, {0.05, 0.01, 0}, {0.1, 0, 0.01}}, 21, 1, 0.1);
  ASSERT_EQ(s.points.size(), 21u);
  EXPECT_LT((s.points.front() - Eigen::Vector3d(0, 0, 0)).norm(), 1e-15);
  EXPECT_LT((s.points.back() - Eigen::Vector3d(0.1, 0, 0.01)).norm(), 1e-12);
  const double step = (s.points[1] - s.points[0]).norm();
  for (std::size_t j = 1; j < s.points.size(); ++j)
    EXPECT_NEAR((s.points[j] - s.points[j - 1]).norm(), step, 0.02 * step);
  for (const Eigen::Matrix3d& A : s.frames) {
    EXPECT_LT((A.transpose() * A - Eigen::Matrix3d::Identity()).norm(), 1e-12);
    EXPECT_NEAR(A.determinant(), 1.0, 1e-12);
  }
}

TEST(DistanceObjective, ATargetsWeightScalesItsValueGradientAndModel)
{
  // [[target]] weight multiplies f_dist in eq. 4, and with it what the optimizers see of it.
  Problem pr;
  Simulation sim(pr.mesh, pr.options());
  const Eigen::VectorXd rest = sim.rest();
  const Eigen::VectorXd target = rest + 1e-3 * Eigen::VectorXd::Random(rest.size());
  const Eigen::VectorXd x = rest + 1e-3 * Eigen::VectorXd::Random(rest.size());
  const Eigen::MatrixXd S = Eigen::MatrixXd::Random(rest.size(), 5);
  const DistanceObjective one(sim.basis(), pr.curves, target), three(sim.basis(), pr.curves, target, 3.0);
  ASSERT_GT(one.value(x), 0);
  EXPECT_NEAR(three.value(x), 3 * one.value(x), 1e-12 * one.value(x));
  EXPECT_LT((three.gradient(x) - 3 * one.gradient(x)).norm(), 1e-12 * one.gradient(x).norm());
  EXPECT_LT((three.gauss_newton_hessian(S) - 3 * one.gauss_newton_hessian(S)).norm(),
            1e-12 * one.gauss_newton_hessian(S).norm());
  // The RMSE is the target's error in mm, whatever its weight.
  EXPECT_EQ(three.rmse(x), one.rmse(x));
}

// The turn's error of a tracking curve: the angle between how the material turned and how the
// target's turned (polar rotations of F and F̂). Bodies turned rigidly, so that F = R exactly (the
// MLS basis reproduces a linear field): 30° asked and 10° reached about the same axis are 20° off
// at every sample; an untracked orientation has no error to give.
TEST(DistanceObjective, TheTurnsErrorIsTheAngleBetweenTheTurnReachedAndTheTurnAsked)
{
  Problem pr;
  Simulation sim(pr.mesh, pr.options());
  const Eigen::VectorXd rest = sim.rest();
  const auto turned = [&](double degrees) {
    const Eigen::Matrix3d R =
        Eigen::AngleAxisd(degrees * M_PI / 180, Eigen::Vector3d(1, 1, 0).normalized()).toRotationMatrix();
    Eigen::VectorXd x(rest.size());
    for (Eigen::Index i = 0; i < rest.size() / 3; ++i) x.segment<3>(3 * i) = R * rest.segment<3>(3 * i);
    return x;
  };
  const Eigen::VectorXd target = turned(30), x = turned(10);
  const DistanceObjective f(sim.basis(), pr.curves, target);
  ASSERT_TRUE(f.tracks_orientation());
  EXPECT_NEAR(f.orientation_errors(x).rms * 180 / M_PI, 20, 1e-6);
  EXPECT_NEAR(f.orientation_errors(x).max * 180 / M_PI, 20, 1e-6);
  EXPECT_NEAR(f.orientation_errors(rest).rms * 180 / M_PI, 30, 1e-6);
  EXPECT_NEAR(f.orientation_errors(target).rms, 0, 1e-6);
  const DistanceObjective untracked(sim.basis(), {sample_tracking_curve({{0, 0, 0}, {kL, 0, 0}}, 12, 1.0, 0)}, target);
  EXPECT_FALSE(untracked.tracks_orientation());
  EXPECT_EQ(untracked.orientation_errors(x).rms, 0);
}

} // namespace
} // namespace fibermold
