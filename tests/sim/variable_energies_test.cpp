// Muscles replaced between solves (as the optimizer moves them): the equilibrium equals that of a
// simulation built with the new muscle; the Hessian pattern grows to fit new stencils.
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
  m.push_back(muscle(moving, model, second));  // on the far side: new node pairs in the pattern
  moving.set_variable_energies(std::move(m));
  ASSERT_TRUE(moving.solve(x, progress).converged);  // warm-started from the first equilibrium

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
  EXPECT_EQ(grown.matrix().nonZeros(), 9 * (5 + 2 + 3));  // diagonal blocks, the old pairs, the new pairs
  EXPECT_EQ(grown.matrix().norm(), 0);
}

} // namespace
} // namespace fibermold
