// Newton's method through a region where the exact Hessian is indefinite only because two stiff
// terms nearly cancel (as a compressed element and its neighbours do near a snap): the shifted
// exact Hessian follows the soft mode, where each term's own projection would make it stiff and
// the steps crawl.
#include <cstdio>
#include <random>

#include <gtest/gtest.h>

#include "sim/external_forces.hpp"
#include "sim/muscle_energy.hpp"
#include "sim/newton_solver.hpp"
#include "sim/simulation.hpp"
#include "sim_fixtures.hpp"

namespace fibermold {
namespace {

/// One node; the energy of its first coordinate is `quadratic`/2 x² + `quartic`/4 x⁴, the other
/// two are held by springs of stiffness `hold`.
class Polynomial final : public Energy {
public:
  Polynomial(double quadratic, double quartic, double hold) : k2_(quadratic), k4_(quartic), hold_(hold) {}
  std::string name() const override { return "polynomial"; }
  double value(const Eigen::VectorXd& x) const override
  {
    return k2_ / 2 * x[0] * x[0] + k4_ / 4 * std::pow(x[0], 4) + hold_ / 2 * (x[1] * x[1] + x[2] * x[2]);
  }
  void add_gradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const override
  {
    g[0] += k2_ * x[0] + k4_ * std::pow(x[0], 3);
    g[1] += hold_ * x[1];
    g[2] += hold_ * x[2];
  }
  void add_hessian(const Eigen::VectorXd& x, SparseHessian& H, bool project) const override
  {
    const double along = k2_ + 3 * k4_ * x[0] * x[0];
    H.add_block(0, 0, Eigen::Vector3d(project ? std::max(along, 0.0) : along, hold_, hold_).asDiagonal());
  }
  void add_hessian_product(const Eigen::VectorXd& x, const Eigen::VectorXd& v, Eigen::VectorXd& out) const override
  {
    out.head<3>() += Eigen::Vector3d(k2_ + 3 * k4_ * x[0] * x[0], hold_, hold_).cwiseProduct(v.head<3>());
  }
  void stencils(std::vector<std::vector<int>>& out) const override { out.push_back({0}); }

private:
  double k2_, k4_, hold_;
};

TEST(NewtonSolver, FollowsASoftModeOfNegativeCurvatureToTheMinimum)
{
  // E = −x²/2 + x⁴/4 from two terms of stiffness ±100: minima at x = ±1, the exact Hessian
  // −1 + 3x² indefinite for |x| < 0.577. Each term projected alone gives 100 there, and steps of
  // (x − x³)/100: from x = 0.05 about 300 of them.
  const Polynomial stiff(100, 0, 1000), cancelling(-101, 1, 0);
  NewtonSolver solver({&stiff, &cancelling}, 1);
  Eigen::VectorXd x = Eigen::Vector3d(0.05, 0.01, -0.01);
  NullProgress progress;
  NewtonOptions options;
  options.tolerance = 1e-12;
  options.quasi_newton_pairs = 0;
  options.reuse_contraction = 0; // one assembly per step
  const NewtonSummary s = solver.solve(x, options, progress);
  ASSERT_TRUE(s.converged) << s.brief();
  EXPECT_NEAR(x[0], 1.0, 1e-10);
  EXPECT_NEAR(x[1], 0.0, 1e-12);
  EXPECT_LE(s.iterations, 15) << s.brief();
  EXPECT_EQ(s.assemblies, s.iterations) << "the projected Hessian was assembled too";
}

TEST(NewtonSolver, FarFromDefiniteFallsBackToTheProjectedHessian)
{
  // Curvature −1000 + 3000x² (−998.8 at the start), so τ ≤ 0.01 × 998.8 cannot make it definite:
  // the projection (and its own shift) must take over, and the minimum is still found.
  const Polynomial well(-1000, 1000, 1);
  NewtonSolver solver({&well}, 1);
  Eigen::VectorXd x = Eigen::Vector3d(-0.02, 0, 0);
  NullProgress progress;
  NewtonOptions options;
  options.quasi_newton_pairs = 0;
  options.reuse_contraction = 0; // one exact assembly per step, and one more where it is projected
  const NewtonSummary s = solver.solve(x, options, progress);
  ASSERT_TRUE(s.converged) << s.brief();
  EXPECT_NEAR(x[0], -1.0, 1e-9);
  EXPECT_GT(s.assemblies, s.iterations) << "the projected Hessian should have been assembled";
}

/// A 40 mm bar clamped at x = 0 with one muscle along it, under the optimizer's Newton settings
/// (kept factorizations, a finishing step on a fresh one).
class MuscleBar : public ::testing::Test {
protected:
  static SimulationOptions options(const TetMesh& mesh)
  {
    SimulationOptions o;
    o.fixed_nodes = {nodes_in_box(mesh.nodes, {-1, -1, -1}, {1e-9, 1, 1})};
    o.newton.finish_on_fresh_step = true;
    return o;
  }
  /// Replaces the muscle by one at pressure p (Pa).
  void set_muscle(double p, int segments = 20)
  {
    std::vector<std::unique_ptr<Energy>> m;
    m.push_back(std::make_unique<MuscleEnergy>(sim.basis(), model, route, segment_parameters(route, segments), p));
    sim.set_variable_energies(std::move(m));
  }
  /// The tolerance on |∇E| of the muscle set (N): as Simulation::solve sets it.
  double goal()
  {
    return o.newton.tolerance *
           (sim.solver().gradient(sim.rest()).norm() + o.youngs_modulus * std::pow(sim.mean_edge_length(), 2));
  }

  const TetMesh mesh = test::box_mesh({0, -0.006, -0.006}, {0.04, 0.006, 0.006}, 0.004);
  const SimulationOptions o = options(mesh);
  Simulation sim{mesh, o};
  const MuscleModel model;
  const HermiteSpline route{{{0, 0.003, 0}, {0.02, 0.004, -0.002}, {0.04, 0.003, 0}}};
};

TEST_F(MuscleBar, FinishingOnAFreshStepLandsFarBelowTheToleranceAndServesTheAdjointSolve)
{
  // A bar bent by a muscle, solved from rest with reused factorizations (the optimizer's setting):
  // the last step is taken on a fresh one, and the adjoint solve with that factorization (the
  // Hessian a few steps before the equilibrium) equals the one with the Hessian at the equilibrium.
  set_muscle(250e3);
  Eigen::VectorXd x = sim.rest();
  NullProgress progress;
  const NewtonSummary s = sim.solve(x, progress);
  ASSERT_TRUE(s.converged) << s.brief();
  EXPECT_LT(s.factorizations, s.iterations) << "some steps should reuse a factorization";
  EXPECT_LT(s.residual, 1e-2 * goal()) << s.brief();

  const Eigen::VectorXd b = Eigen::VectorXd::Random(x.size());
  Eigen::VectorXd reused, assembled;
  ASSERT_TRUE(sim.solver().solve_with_hessian(x, b, reused));
  set_muscle(250e3); // the same muscle again: the factorization is forgotten
  // The pattern is kept (MLS), so the muscle's far pairs are lumped, and the assembled solve is
  // conjugate gradients on the exact Hessian's products, preconditioned by that factorization.
  ASSERT_TRUE(sim.solver().solve_with_hessian(x, b, assembled));
  EXPECT_GT(sim.solver().hessian(x, false).lumped(), 0);
  EXPECT_EQ(sim.symbolic_analyses(), 1);
  std::printf("adjoint solve with the last step's factorization: relative difference %.1e\n",
              (reused - assembled).norm() / assembled.norm());
  // The adjoint gradient is checked to 1e-6 against finite differences; this is 10× inside it.
  EXPECT_LT((reused - assembled).norm(), 1e-7 * assembled.norm());
  EXPECT_GT((reused - assembled).norm(), 0.0) << "the reused factorization is of a state a few steps before x";

  // Anywhere else the Hessian is assembled there: a second call, which assembles, agrees exactly.
  const Eigen::VectorXd y = x + 1e-6 * Eigen::VectorXd::Random(x.size());
  ASSERT_TRUE(sim.solve(x, progress).converged);
  Eigen::VectorXd first, second;
  ASSERT_TRUE(sim.solver().solve_with_hessian(y, b, first));
  ASSERT_TRUE(sim.solver().solve_with_hessian(y, b, second));
  EXPECT_EQ(first, second);
}

TEST_F(MuscleBar, NearTheToleranceALumpedHessianStillTakesNewtonSteps)
{
  // A muscle of 4 segments (each 10 mm long) couples nodes farther apart than the elastic
  // energy's pattern, and the pattern is kept (MLS): those pairs are lumped, so the factorization
  // is not of the exact Hessian. Near the tolerance the step is the exact one all the same
  // (conjugate gradients preconditioned by it): from ~300× the tolerance |∇E| falls to 1e-2× it
  // in a step or two on one assembly (conjugate gradients take 23 products here: the muscle is
  // strong for the bar). On the lumped Hessian alone that took 19 steps and 10 assemblies, each
  // shrinking |∇E| by a fixed factor, and ended at 4.4e-2× the tolerance.
  NullProgress progress;
  const auto near_equilibrium = [&](int segments, double& goal) {
    set_muscle(250e3, segments);
    Eigen::VectorXd x = sim.rest();
    EXPECT_TRUE(sim.solve(x, progress).converged);
    EXPECT_GT(sim.solver().hessian(x, false).lumped(), 0);
    goal = this->goal();
    std::mt19937 random(segments);
    std::normal_distribution<double> normal;
    Eigen::VectorXd direction(x.size());
    for (Eigen::Index k = 0; k < direction.size(); ++k) direction[k] = normal(random);
    direction.normalize();
    const double unit = sim.solver().gradient(x + 1e-9 * direction).norm() / 1e-9; // |∇E| per m along it
    const Eigen::VectorXd y = x + 300 * goal / unit * direction;
    const double start = sim.solver().gradient(y).norm();
    EXPECT_GT(start, 100 * goal);
    EXPECT_LT(start, 1e3 * goal);
    set_muscle(250e3, segments); // the factorization is forgotten
    return y;
  };
  double goal = 0;
  Eigen::VectorXd y = near_equilibrium(4, goal);
  NewtonSummary s = sim.solve(y, progress);
  ASSERT_TRUE(s.converged) << s.brief();
  EXPECT_LT(s.residual, 1e-2 * goal) << s.brief();
  EXPECT_EQ(s.assemblies, 1) << s.brief();
  EXPECT_LE(s.iterations, 2) << s.brief();
  std::printf("exact Newton steps: %d Hessian products\n", s.products);
  EXPECT_GT(s.products, 0);
  // Two segments of 20 mm: the lumped pairs are too heavy for the factorization to precondition
  // conjugate gradients within their 40 products, and the solve goes on with its own steps: the
  // products were tried once, not again at every fresh factorization.
  y = near_equilibrium(2, goal);
  s = sim.solve(y, progress);
  ASSERT_TRUE(s.converged) << s.brief();
  EXPECT_LE(s.residual, goal) << s.brief();
  EXPECT_GT(s.iterations, 2) << s.brief();
  EXPECT_GT(s.assemblies, 1) << s.brief();
  EXPECT_GT(s.products, 0) << s.brief();
  EXPECT_LE(s.products, 40) << s.brief();
}

TEST_F(MuscleBar, ASolveFromWhereTheLastEndedBeginsOnItsFactorization)
{
  // The optimizer's warm start: the muscle's pressure changes a little and the solve starts at the
  // last equilibrium. The factorization of its finishing step serves the first steps, so that only
  // the finishing step assembles; from anywhere else the first step assembles too.
  set_muscle(250e3);
  Eigen::VectorXd x = sim.rest();
  NullProgress progress;
  ASSERT_TRUE(sim.solve(x, progress).converged);
  const Eigen::VectorXd first = x;

  set_muscle(252e3);
  const NewtonSummary warm = sim.solve(x, progress);
  ASSERT_TRUE(warm.converged) << warm.brief();
  EXPECT_EQ(warm.assemblies, 1) << warm.brief();
  EXPECT_GT(warm.iterations, 1);

  Eigen::VectorXd elsewhere = first + 1e-9 * Eigen::VectorXd::Ones(first.size());
  const NewtonSummary cold = sim.solve(elsewhere, progress);
  ASSERT_TRUE(cold.converged) << cold.brief();
  EXPECT_EQ(cold.assemblies, 2) << cold.brief();
  const double moved = (x - first).cwiseAbs().maxCoeff();
  std::printf("2 kPa more moves a node by up to %.3e m; the two solves differ by %.1e m\n", moved,
              (x - elsewhere).cwiseAbs().maxCoeff());
  EXPECT_GT(moved, 1e-6);
  EXPECT_LT((x - elsewhere).cwiseAbs().maxCoeff(), 1e-3 * moved);
}

} // namespace
TEST_F(MuscleBar, SolvesAlternatingBetweenTwoLoadsEachBeginOnTheirOwnSolversFactorization)
{
  // The optimizer's two targets: 150 and 250 kPa, each warm-started from its own last equilibrium.
  // On solvers of their own each solve after the first assembles only for its finishing step; on
  // one shared solver each starts on the other load's factorization and assembles at its start too.
  NullProgress progress;
  const auto alternate = [&](bool own_solvers) {
    std::vector<Eigen::VectorXd> x(2, sim.rest());
    int assemblies = 0;
    for (int round = 0; round < 3; ++round)
      for (int load = 0; load < 2; ++load) {
        sim.use_solver(own_solvers ? 2 + load : 1);
        set_muscle((load == 0 ? 150e3 : 250e3) + 1e3 * round);
        const NewtonSummary s = sim.solve(x[load], progress);
        EXPECT_TRUE(s.converged) << s.brief();
        if (round > 0) assemblies += s.assemblies;
      }
    return assemblies;
  };
  const int shared = alternate(false), own = alternate(true);
  std::printf("rounds 2 and 3, 4 solves: %d assemblies on one solver, %d on one per load\n", shared, own);
  EXPECT_EQ(own, 4);
  EXPECT_EQ(shared, 8);
}

} // namespace fibermold
