// One generic finite-difference test over every energy (after polyfem's test_form_derivatives):
// value → gradient and gradient → Hessian, at random states near rest, relative error ≤ 1e-6; the
// Hessian's product against the assembled Hessian.
#include <functional>
#include <random>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "finite_differences.hpp"
#include "mesh/mesh_quality.hpp"
#include "sim/external_forces.hpp"
#include "sim/mls_basis.hpp"
#include "sim/muscle_energy.hpp"
#include "sim/neo_hookean.hpp"
#include "sim/soft_dirichlet.hpp"
#include "sim_fixtures.hpp"

namespace fibermold {
namespace {

struct Body {
  TetMesh mesh = test::box_mesh({0, 0, 0}, {0.02, 0.01, 0.01}, 0.005);
  MlsBasis basis{mesh.nodes, {false, 1.7 * mesh_quality(mesh).mean_edge_length}};
  QuadraturePoints qp = build_quadrature_points(mesh, basis, 8);
  Eigen::Index n = mesh.nodes.rows();

  Eigen::VectorXd random_state(unsigned seed, double amplitude) const
  {
    std::mt19937 random(seed);
    std::normal_distribution<double> noise(0, amplitude);
    Eigen::VectorXd x(3 * n);
    for (Eigen::Index i = 0; i < n; ++i) {
      const Eigen::Vector3d X = mesh.nodes.row(i).transpose();
      x.segment<3>(3 * i) = Eigen::Vector3d(X.x() + 0.1 * X.y(), X.y() - 0.05 * X.z(), X.z() * 1.1) +
                            Eigen::Vector3d(noise(random), noise(random), noise(random));
    }
    return x;
  }
};

using Factory = std::function<std::unique_ptr<Energy>(const Body&)>;

struct Named {
  std::string name;
  Factory make;
};

std::vector<Named> energies()
{
  return {
      {"neo_hookean",
       [](const Body& b) {
         return std::make_unique<NeoHookean>(b.qp, b.n, LameParameters::from_young_poisson(86.4e3, 0.47));
       }},
      {"soft_dirichlet",
       [](const Body& b) {
         std::vector<ShapeEval> at;
         std::vector<Eigen::Vector3d> targets;
         for (int i : nodes_in_box(b.mesh.nodes, {-1, -1, -1}, {0.0001, 1, 1})) {
           at.push_back(b.basis.at(b.mesh.nodes.row(i).transpose(), 0));
           targets.push_back(b.mesh.nodes.row(i).transpose());
         }
         return std::make_unique<SoftDirichlet>(std::move(at), std::move(targets), 1e4 * 86.4e3 * 0.005);
       }},
      {"muscle",
       [](const Body& b) {
         static const MuscleModel model;
         const HermiteSpline fiber({{0.001, 0.003, 0.004}, {0.01, 0.006, 0.005}, {0.019, 0.004, 0.007}});
         return std::make_unique<MuscleEnergy>(b.basis, model, fiber, segment_parameters(fiber, 12), 300e3);
       }},
      {"gravity",
       [](const Body& b) {
         return std::make_unique<ExternalForces>(gravity_forces(nodal_masses(b.qp, b.n, 1070), {0, 0, -9.81}));
       }},
  };
}

class EnergyDerivatives : public ::testing::TestWithParam<int> {};

TEST_P(EnergyDerivatives, GradientAndHessianMatchFiniteDifferences)
{
  const Body body;
  const std::vector<Named> all = energies();
  const Named& named = all[GetParam()];
  SCOPED_TRACE(named.name);
  const auto energy = named.make(body);
  std::vector<std::vector<int>> stencils;
  energy->stencils(stencils);
  SparseHessian H(body.n, stencils);
  for (unsigned seed : {1u, 2u}) {
    const Eigen::VectorXd x = body.random_state(seed, 2e-4);
    ASSERT_TRUE(energy->is_step_valid(x));
    Eigen::VectorXd g = Eigen::VectorXd::Zero(x.size());
    energy->add_gradient(x, g);
    ASSERT_GT(g.norm(), 0) << "nothing to check";
    H.set_zero();
    energy->add_hessian(x, H, false);
    const Eigen::MatrixXd Hd = Eigen::MatrixXd(H.full());

    // Central differences along random directions.
    std::mt19937 random(seed);
    std::normal_distribution<double> normal;
    const test::ScalarFunction value = [&](const Eigen::VectorXd& y) { return energy->value(y); };
    const test::VectorFunction gradient = [&](const Eigen::VectorXd& y) {
      Eigen::VectorXd gy = Eigen::VectorXd::Zero(y.size());
      energy->add_gradient(y, gy);
      return gy;
    };
    const double h = 1e-7;
    for (int trial = 0; trial < 6; ++trial) {
      Eigen::VectorXd d(x.size());
      for (Eigen::Index k = 0; k < d.size(); ++k) d[k] = normal(random);
      d.normalize();
      EXPECT_TRUE(test::matches_fd(g.dot(d), test::central_difference(value, x, d, h), test::kFdTolerance,
                                   1e-6 * g.norm() + 1e-12))
          << "gradient, trial " << trial;
      EXPECT_TRUE(test::matches_fd(Hd * d, test::central_difference(gradient, x, d, h), test::kFdTolerance,
                                   1e-15 * Hd.norm() + 1e-12))
          << "Hessian, trial " << trial;
      // The product conjugate gradients use: in closed form (elastic, muscle, springs, loads) it is
      // the assembled Hessian's to round-off.
      Eigen::VectorXd Hv = Eigen::VectorXd::Constant(x.size(), 1.0);
      energy->add_hessian_product(x, d, Hv);
      Hv.array() -= 1.0;
      EXPECT_TRUE(test::matches_fd(Hd * d, Hv, 1e-12, 1e-15 * Hd.norm() + 1e-12)) << "Hessian product, trial " << trial;
      // The operator at x that conjugate gradients build once: the same bits, product after product.
      const auto at_x = energy->hessian_at(x);
      for (int twice = 0; twice < 2; ++twice) {
        Eigen::VectorXd again = Eigen::VectorXd::Constant(x.size(), 1.0);
        at_x->add(d, again);
        again.array() -= 1.0;
        EXPECT_EQ(again, Hv) << "trial " << trial;
      }
    }
    EXPECT_LE((Hd - Hd.transpose()).norm(), 1e-12 * std::max(1.0, Hd.norm()));
  }
}

INSTANTIATE_TEST_SUITE_P(Energies, EnergyDerivatives, ::testing::Range(0, 4));

TEST(MuscleEnergy, ItsHessianProductIsTheExactHessiansWhereTheAssemblyLumpsPairs)
{
  // A pattern of the nodes alone (as a kept pattern lacks a moved fiber's far pairs): the assembly
  // lumps every pair of the muscle onto the diagonal. The product conjugate gradients use must be
  // of the exact Hessian, the full pattern's, not of the lumped one it preconditions with.
  const Body body;
  const auto muscle = energies()[2].make(body);
  ASSERT_EQ(muscle->name(), "muscle");
  std::vector<std::vector<int>> stencils, nodes_alone;
  muscle->stencils(stencils);
  for (int i = 0; i < body.n; ++i) nodes_alone.push_back({i});
  SparseHessian full(body.n, stencils), lumped(body.n, nodes_alone);
  const Eigen::VectorXd x = body.random_state(3, 2e-4);
  muscle->add_hessian(x, full, false);
  muscle->add_hessian(x, lumped, false);
  ASSERT_GT(lumped.lumped(), 0);
  ASSERT_EQ(full.lumped(), 0);
  std::mt19937 random(4);
  std::normal_distribution<double> normal;
  Eigen::VectorXd v(x.size());
  for (Eigen::Index k = 0; k < v.size(); ++k) v[k] = normal(random);
  Eigen::VectorXd Hv = Eigen::VectorXd::Zero(x.size());
  muscle->hessian_at(x)->add(v, Hv);
  const Eigen::VectorXd exact = Eigen::MatrixXd(full.full()) * v, approximate = Eigen::MatrixXd(lumped.full()) * v;
  EXPECT_LE((Hv - exact).norm(), 1e-12 * exact.norm());
  EXPECT_GT((Hv - approximate).norm(), 1e-3 * exact.norm()); // the lumped Hessian is another matrix
}

TEST(NeoHookean, StressIsTheDerivativeOfTheDensity)
{
  const LameParameters l = LameParameters::from_young_poisson(86.4e3, 0.47);
  const Eigen::Matrix3d F = (Eigen::Matrix3d() << 1.1, 0.2, 0.0, -0.1, 0.95, 0.15, 0.05, 0.0, 1.2).finished();
  const Eigen::Matrix3d P = neo_hookean_stress(F, l);
  const Eigen::Matrix<double, 9, 9> D = neo_hookean_stress_derivative(F, l);
  // F flattened row by row, as D's indices are: 3 i + j.
  const auto matrix = [](const Eigen::VectorXd& f) { return Eigen::Matrix3d(f.reshaped<Eigen::RowMajor>(3, 3)); };
  const Eigen::VectorXd f = F.reshaped<Eigen::RowMajor>();
  const test::ScalarFunction density = [&](const Eigen::VectorXd& y) { return neo_hookean_density(matrix(y), l); };
  const test::VectorFunction stress = [&](const Eigen::VectorXd& y) {
    return Eigen::VectorXd(neo_hookean_stress(matrix(y), l).reshaped<Eigen::RowMajor>());
  };
  EXPECT_TRUE(test::matches_fd(P.reshaped<Eigen::RowMajor>(), test::fd_gradient(density, f, 1e-7)));
  EXPECT_TRUE(test::matches_fd(D, test::fd_jacobian(stress, f, 1e-7)));
  EXPECT_EQ(neo_hookean_density(-Eigen::Matrix3d::Identity(), l), HUGE_VAL); // inverted: no energy defined
}

TEST(NeoHookean, ClosedFormProjectionEqualsTheEigendecomposition)
{
  const auto project_psd = [](const Eigen::Matrix<double, 9, 9>& A) -> Eigen::Matrix<double, 9, 9> {
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 9, 9>> eig(A);
    return eig.eigenvectors() * eig.eigenvalues().cwiseMax(0).asDiagonal() * eig.eigenvectors().transpose();
  };
  // Stretched, sheared, compressed beyond ln J = μ/λ (where c < 0), near rest (equal singular values).
  const LameParameters l = LameParameters::from_young_poisson(86.4e3, 0.47);
  std::mt19937 random(7);
  std::uniform_real_distribution<double> entry(-0.6, 0.6);
  std::vector<Eigen::Matrix3d> states = {Eigen::Matrix3d::Identity(), 1.3 * Eigen::Matrix3d::Identity(),
                                         Eigen::Vector3d(0.5, 0.5, 2.0).asDiagonal().toDenseMatrix()};
  for (int trial = 0; trial < 40; ++trial) {
    Eigen::Matrix3d F = Eigen::Matrix3d::Identity();
    for (int k = 0; k < 9; ++k) F(k / 3, k % 3) += (trial < 20 ? 1e-3 : 1.0) * entry(random);
    if (F.determinant() > 0.05) states.push_back(F);
  }
  int projected = 0;
  for (const Eigen::Matrix3d& F : states) {
    const Eigen::Matrix<double, 9, 9> reference = project_psd(neo_hookean_stress_derivative(F, l));
    const Eigen::Matrix<double, 9, 9> closed_form = neo_hookean_stress_derivative_psd(F, l);
    EXPECT_LE((closed_form - reference).norm(), 1e-10 * reference.norm()) << F;
    projected += (reference - neo_hookean_stress_derivative(F, l)).norm() > 1e-6 * reference.norm();
  }
  EXPECT_GE(projected, 20); // most states have a negative mode to remove
}

TEST(NeoHookean, RigidMotionHasZeroEnergyAndForce)
{
  const Body body;
  const NeoHookean e(body.qp, body.n, LameParameters::from_young_poisson(86.4e3, 0.47));
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  Eigen::VectorXd x(3 * body.n);
  for (Eigen::Index i = 0; i < body.n; ++i)
    x.segment<3>(3 * i) = R * body.mesh.nodes.row(i).transpose() + Eigen::Vector3d(0.1, -0.2, 0.3);
  EXPECT_NEAR(e.value(x), 0, 1e-15);
  Eigen::VectorXd g = Eigen::VectorXd::Zero(x.size());
  e.add_gradient(x, g);
  EXPECT_LT(g.norm(), 1e-12);
}

} // namespace
} // namespace fibermold
