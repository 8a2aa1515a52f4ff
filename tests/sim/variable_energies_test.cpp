// Muscles replaced between solves (as the optimizer moves them): the equilibrium equals that of a
// simulation built with the new muscle; the Hessian pattern grows to fit new stencils.
#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

#include "sim/external_forces.hpp"
#include "sim/muscle_energy.hpp"
#include "sim/simulation.hpp"
#include "sim_fixtures.hpp"

namespace fibermold {
namespace {

constexpr double kL = 0.04, kA = 0.012;

SimulationOptions held(const TetMesh& mesh)
{
  SimulationOptions o;
  o.fixed_nodes = {nodes_in_box(mesh.nodes, {-1, -1, -1}, {1e-9, 1, 1})};
  o.newton.tolerance = 1e-10;
  return o;
}

std::unique_ptr<MuscleEnergy> muscle(const Simulation& sim, const MuscleModel& model, const HermiteSpline& s)
{
  return std::make_unique<MuscleEnergy>(sim.basis(), model, s, segment_parameters(s, 20), 250e3);
}

TEST(VariableEnergies, ReplacedMusclesGiveTheSameEquilibriumAsAFreshSimulation)
{
  const TetMesh mesh = test::box_mesh({0, -kA / 2, -kA / 2}, {kL, kA / 2, kA / 2}, 0.004);
  const MuscleModel model;
  const HermiteSpline first({{0, -0.004, 0}, {kL, -0.004, 0}}), second({{0, 0.004, 0.003}, {kL, 0.004, -0.003}});
  NullProgress progress;

  Simulation moving(mesh, held(mesh));
  std::vector<std::unique_ptr<Energy>> m;
  m.push_back(muscle(moving, model, first));
  moving.set_variable_energies(std::move(m));
  Eigen::VectorXd x = moving.rest();
  ASSERT_TRUE(moving.solve(x, progress).converged);
  m.clear();
  m.push_back(muscle(moving, model, second)); // on the far side: new node pairs in the pattern
  moving.set_variable_energies(std::move(m));
  ASSERT_TRUE(moving.solve(x, progress).converged); // warm-started from the first equilibrium

  Simulation fresh(mesh, held(mesh));
  fresh.add_energy(muscle(fresh, model, second));
  Eigen::VectorXd y = fresh.rest();
  ASSERT_TRUE(fresh.solve(y, progress).converged);
  EXPECT_LT((x - y).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_GT((y - fresh.rest()).cwiseAbs().maxCoeff(), 1e-3) << "the muscle should move the bar by millimetres";
}

TEST(SparseHessian, GrowsToFitNewStencilsKeepingTheOldPairs)
{
  const SparseHessian base(5, {{0, 1}, {2, 3}});
  EXPECT_TRUE(base.contains({{1, 0}, {3, 2}, {4}}));
  EXPECT_FALSE(base.contains({{1, 2}}));
  const SparseHessian grown(base, {{1, 2, 4}});
  EXPECT_TRUE(grown.contains({{0, 1}, {2, 3}, {1, 2, 4}}));
  EXPECT_FALSE(grown.contains({{0, 4}}));
  EXPECT_EQ(grown.matrix().nonZeros(), 9 * (5 + 2 + 3)); // diagonal blocks, the old pairs, the new pairs
  EXPECT_EQ(grown.matrix().norm(), 0);
}

TEST(SparseHessian, ACouplingOutsideThePatternIsLumpedOntoTheDiagonalKeepingItDefinite)
{
  SparseHessian H(3, {{0, 1}});
  const Eigen::Matrix3d M = Eigen::Vector3d(2, 1, 0.5).asDiagonal();
  // Two muscle-like pairs, each [[3M, −3M], [−3M, 3M]] (positive semi-definite): (0, 1) in the
  // pattern, (0, 2) not, so its coupling goes onto the diagonal: 3M more at 0 and at 2.
  for (const auto& [a, b] : {std::pair{1, 0}, std::pair{0, 2}}) {
    H.add_block(a, a, 3 * M);
    H.add_block(b, b, 3 * M);
    H.add_coupling(a, b, -3, M);
  }
  EXPECT_EQ(H.lumped(), 1);
  const Eigen::MatrixXd full = H.full();
  const Eigen::Matrix3d off = full.block(0, 3, 3, 3), first = full.block(0, 0, 3, 3), last = full.block(6, 6, 3, 3);
  EXPECT_EQ((off + 3 * M).norm(), 0);
  EXPECT_EQ((first - 9 * M).norm(), 0);
  EXPECT_EQ((last - 6 * M).norm(), 0);
  EXPECT_EQ(full.block(0, 6, 3, 3).norm(), 0);
  EXPECT_GT(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(full).eigenvalues().minCoeff(), -1e-12);
  H.set_zero();
  EXPECT_EQ(H.lumped(), 0);
}

/// The symbolic analyses of a simulation whose muscle moves to the far side of the bar.
int analyses_after_moving_the_muscle(Simulation& sim)
{
  const MuscleModel model;
  NullProgress progress;
  Eigen::VectorXd x = sim.rest();
  for (const HermiteSpline& s :
       {HermiteSpline({{0, -0.004, 0}, {kL, -0.004, 0}}), HermiteSpline({{0, 0.004, 0.003}, {kL, 0.004, -0.003}})}) {
    std::vector<std::unique_ptr<Energy>> m;
    m.push_back(muscle(sim, model, s));
    sim.set_variable_energies(std::move(m));
    EXPECT_TRUE(sim.solve(x, progress).converged);
  }
  return sim.symbolic_analyses();
}

/// With an MLS basis the pattern is kept (newton_solver.hpp): a muscle moved to the far side of the
/// bar is solved on the first analysis (ReplacedMuscles… above checks its equilibrium); with FEM
/// the pattern grows to fit it, and CHOLMOD analyses it again.
TEST(VariableEnergies, AKeptPatternIsAnalysedOnceAGrowingOneAgain)
{
  const TetMesh mesh = test::box_mesh({0, -kA / 2, -kA / 2}, {kL, kA / 2, kA / 2}, 0.004);
  Simulation mls(mesh, held(mesh));
  EXPECT_EQ(analyses_after_moving_the_muscle(mls), 1);
  SimulationOptions grows = held(mesh);
  grows.basis = BasisKind::fem_p1;
  Simulation fem(mesh, grows);
  EXPECT_EQ(analyses_after_moving_the_muscle(fem), 2);
}

} // namespace
} // namespace fibermold
