// The L-BFGS correction of a kept factorization (sim/lbfgs_correction.hpp): the secant equation, the
// pairs it refuses, its memory, and what it saves Newton from rest.
#include <cstdio>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include "sim/external_forces.hpp"
#include "sim/lbfgs_correction.hpp"
#include "sim/muscle_energy.hpp"
#include "sim/simulation.hpp"
#include "sim_fixtures.hpp"

namespace fibermold {
namespace {

/// A random symmetric positive definite matrix with eigenvalues from 1 to 100.
Eigen::MatrixXd spd(int n)
{
  const Eigen::MatrixXd q = Eigen::MatrixXd::Random(n, n).householderQr().householderQ();
  return q * Eigen::VectorXd::LinSpaced(n, 1, 100).asDiagonal() * q.transpose();
}

TEST(LbfgsCorrection, WithoutPairsAppliesTheInitialInverse)
{
  const LbfgsCorrection none(8);
  const Eigen::VectorXd g = Eigen::VectorXd::Random(5);
  EXPECT_EQ(none.apply(g, [](const Eigen::VectorXd& q) { return Eigen::VectorXd(2 * q); }), 2 * g);
}

TEST(LbfgsCorrection, TheUpdateMeetsTheSecantEquationOfItsNewestPair)
{
  // On a quadratic with Hessian A, each pair has y = A s; the updated inverse maps the newest y to
  // its s (Nocedal & Wright eq. 6.17), whatever the initial inverse (here the identity).
  const int n = 12;
  const Eigen::MatrixXd A = spd(n);
  LbfgsCorrection c(4);
  const auto identity = [](const Eigen::VectorXd& q) { return q; };
  for (int k = 0; k < 6; ++k) {
    const Eigen::VectorXd s = Eigen::VectorXd::Random(n);
    c.add(s, A * s);
    const Eigen::VectorXd back = c.apply(A * s, identity);
    EXPECT_LT((back - s).norm(), 1e-12 * s.norm()) << "after pair " << k;
    // Positive definite: a descent direction for any gradient.
    const Eigen::VectorXd g = Eigen::VectorXd::Random(n);
    EXPECT_GT(g.dot(c.apply(g, identity)), 0);
  }
  EXPECT_EQ(c.size(), 4u) << "the oldest pairs are dropped";
  // With the exact inverse as H₀, pairs from the same quadratic change nothing.
  const Eigen::MatrixXd Ainv = A.inverse();
  const Eigen::VectorXd g = Eigen::VectorXd::Random(n);
  EXPECT_LT((c.apply(g, [&](const Eigen::VectorXd& q) { return Eigen::VectorXd(Ainv * q); }) - Ainv * g).norm(),
            1e-10 * (Ainv * g).norm());
}

TEST(LbfgsCorrection, RefusesAPairOfNegativeCurvature)
{
  LbfgsCorrection c(4);
  const Eigen::Vector3d s(1, 0, 0);
  c.add(s, Eigen::Vector3d(-1, 0.5, 0));
  c.add(s, Eigen::Vector3d(0, 1, 0)); // sᵀy = 0
  EXPECT_EQ(c.size(), 0u);
  c.add(s, Eigen::Vector3d(2, 0, 0));
  EXPECT_EQ(c.size(), 1u);
}

TEST(LbfgsCorrection, NewtonFromRestFactorizesLessAndReachesTheSameEquilibrium)
{
  // A 60 mm bar clamped at x = 0, bent and twisted by a muscle at 300 kPa from rest: steps on a
  // kept factorization corrected by the pairs against plain steps on it.
  const TetMesh mesh = test::box_mesh({0, -0.006, -0.006}, {0.06, 0.006, 0.006}, 0.004);
  const MuscleModel model;
  const HermiteSpline route{{{0, 0.003, 0}, {0.03, 0.0, 0.004}, {0.06, -0.003, 0}}};
  NewtonSummary summary[2];
  Eigen::VectorXd x[2];
  for (int qn : {0, 1}) {
    SimulationOptions o;
    o.fixed_nodes = {nodes_in_box(mesh.nodes, {-1, -1, -1}, {1e-9, 1, 1})};
    o.newton.quasi_newton_pairs = qn ? 8 : 0;
    Simulation sim(mesh, o);
    sim.add_energy(std::make_unique<MuscleEnergy>(sim.basis(), model, route, segment_parameters(route, 30), 300e3));
    x[qn] = sim.rest();
    NullProgress progress;
    summary[qn] = sim.solve(x[qn], progress);
    ASSERT_TRUE(summary[qn].converged) << summary[qn].brief();
    std::printf("%s: %d steps, %d factorizations\n", qn ? "quasi-Newton" : "plain reuse", summary[qn].iterations,
                summary[qn].factorizations);
  }
  EXPECT_LT(summary[1].factorizations, summary[0].factorizations);
  EXPECT_LT((x[1] - x[0]).cwiseAbs().maxCoeff(), 1e-8); // m: the same equilibrium, to the tolerance
}

} // namespace
} // namespace fibermold
