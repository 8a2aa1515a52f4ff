// The paper's validation (section VIII-A, Fig. 8 top): a 100 × 15 × 15 mm EcoFlex bar clamped at
// one end, hanging under gravity. MLS-linear against fem-p2 on a finer mesh, at the fem-p2 nodes:
// the paper reports RMSE 1.01 mm and max 1.82 mm.
#include <cmath>

#include <gtest/gtest.h>

#include "sim/external_forces.hpp"
#include "sim/simulation.hpp"
#include "sim_fixtures.hpp"

namespace fibermold {
namespace {

constexpr double kL = 0.1, kA = 0.015;

struct Result {
  TetMesh mesh;
  std::unique_ptr<Simulation> sim;
  Eigen::VectorXd x;
  NewtonSummary summary;
};

Result hang(const std::string& basis, double edge, double gravity_scale)
{
  Result r;
  r.mesh = test::box_mesh({0, -kA / 2, -kA / 2}, {kL, kA / 2, kA / 2}, edge, basis == "fem-p2");
  SimulationOptions o;
  o.basis = *value_in(kBasisNames, basis);
  o.gravity = {0, 0, -9.81 * gravity_scale};
  o.fixed_nodes = {nodes_in_box(r.mesh.nodes, {-1e-3, -1, -1}, {1e-9, 1, 1})};
  r.sim = std::make_unique<Simulation>(r.mesh, o);
  r.x = r.sim->rest();
  NullProgress progress;
  r.summary = r.sim->solve(r.x, progress);
  return r;
}

/// Displacement of the deformation field at rest point X.
Eigen::Vector3d displacement(const Result& r, const Eigen::Vector3d& X)
{
  return r.sim->basis().at(X, 0).position(r.x) - X;
}

TEST(Cantilever, MlsLinearMatchesFemP2AtLeastAsWellAsThePaper)
{
  const Result fem = hang("fem-p2", 0.004, 1.0);
  ASSERT_TRUE(fem.summary.converged) << fem.summary.brief();
  const Result mls = hang("mls-linear", 0.004, 1.0);
  ASSERT_TRUE(mls.summary.converged) << mls.summary.brief();

  double sum = 0, worst = 0;
  for (Eigen::Index i = 0; i < fem.mesh.nodes.rows(); ++i) {
    const Eigen::Vector3d X = fem.mesh.nodes.row(i).transpose();
    const Eigen::Vector3d u_fem = fem.x.segment<3>(3 * i) - X;
    const double e = (displacement(mls, X) - u_fem).norm();
    sum += e * e;
    worst = std::max(worst, e);
  }
  const double rmse = std::sqrt(sum / static_cast<double>(fem.mesh.nodes.rows()));
  const double tip = -displacement(fem, {kL, 0, 0}).z();
  RecordProperty("tip_deflection_fem_p2_mm", std::to_string(tip * 1e3));
  RecordProperty("rmse_mm", std::to_string(rmse * 1e3));
  RecordProperty("max_error_mm", std::to_string(worst * 1e3));
  std::printf("cantilever: tip deflection %.2f mm (fem-p2, %ld tets); MLS-linear (%ld tets) RMSE %.3f mm, max %.3f mm "
              "(paper: 1.01, 1.82)\n",
              tip * 1e3, static_cast<long>(fem.mesh.num_tets()), static_cast<long>(mls.mesh.num_tets()), rmse * 1e3,
              worst * 1e3);
  EXPECT_GT(tip, 0.03); // a large, non-linear deflection
  EXPECT_LE(rmse, 1.01e-3);
  EXPECT_LE(worst, 1.82e-3);
}

TEST(Cantilever, SmallLoadTipDeflectionMatchesEulerBernoulli)
{
  // w = q L⁴ / (8 E I), q = ρ g A, I = a⁴ / 12, under a load 20× smaller than gravity.
  const double q = 1070 * 9.81 / 20 * kA * kA, I = std::pow(kA, 4) / 12;
  const double theory = q * std::pow(kL, 4) / (8 * 86.4e3 * I);
  for (const char* basis : {"mls-linear", "fem-p2"}) {
    const Result r = hang(basis, 0.004, 1.0 / 20);
    ASSERT_TRUE(r.summary.converged) << r.summary.brief();
    const double tip = -displacement(r, {kL, 0, 0}).z();
    std::printf("%s: tip %.3f mm, Euler–Bernoulli %.3f mm, ratio %.4f\n", basis, tip * 1e3, theory * 1e3, tip / theory);
    EXPECT_NEAR(tip / theory, 1.0, 0.05) << basis;
  }
}

} // namespace
} // namespace fibermold
