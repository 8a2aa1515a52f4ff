// Derivatives of the muscle energy in the fiber's parameters (spline points, tangents) and the
// pressure, and of λ·∂E/∂x (the adjoint's mixed term, eq. 9), against central finite differences.
#include <functional>
#include <random>

#include <gtest/gtest.h>

#include "finite_differences.hpp"
#include "mesh/mesh_quality.hpp"
#include "sim/mls_basis.hpp"
#include "sim/muscle_energy.hpp"
#include "sim_fixtures.hpp"

namespace fibermold {
namespace {

struct Fixture {
  TetMesh mesh = test::box_mesh({0, 0, 0}, {0.03, 0.012, 0.012}, 0.004);
  MlsBasis basis{mesh.nodes, {false, 1.7 * mesh_quality(mesh).mean_edge_length}};
  MuscleModel model;
  std::vector<Eigen::Vector3d> points{
      {0.002, 0.006, 0.006}, {0.012, 0.004, 0.007}, {0.021, 0.007, 0.005}, {0.028, 0.006, 0.006}};
  std::vector<Eigen::Vector3d> tangents = HermiteSpline(points).tangents();
  std::vector<double> t = segment_parameters(HermiteSpline(points), 16);
  Eigen::VectorXd x, lambda;

  Fixture()
  {
    std::mt19937 random(4);
    std::normal_distribution<double> noise(0, 3e-4);
    x.resize(3 * mesh.nodes.rows());
    lambda.resize(x.size());
    for (Eigen::Index i = 0; i < mesh.nodes.rows(); ++i) {
      const Eigen::Vector3d X = mesh.nodes.row(i).transpose();
      x.segment<3>(3 * i) = Eigen::Vector3d(0.95 * X.x(), X.y() + 0.1 * X.x(), X.z()) +
                            Eigen::Vector3d(noise(random), noise(random), noise(random));
      lambda.segment<3>(3 * i) = 1e3 * Eigen::Vector3d(noise(random), noise(random), noise(random));
    }
  }
  MuscleEnergy energy(const std::vector<Eigen::Vector3d>& p, const std::vector<Eigen::Vector3d>& tg,
                      double pressure) const
  {
    return MuscleEnergy(basis, model, HermiteSpline(p, tg), t, pressure);
  }
  double phi(const MuscleEnergy& e) const
  {
    Eigen::VectorXd g = Eigen::VectorXd::Zero(x.size());
    e.add_gradient(x, g);
    return lambda.dot(g);
  }
};

/// Compares an analytic parameter gradient with central differences of `f` over every coordinate.
void check(const Fixture& fx, const FiberParameterGradient& analytic, double pressure,
           const std::function<double(const MuscleEnergy&)>& f)
{
  const test::ScalarFunction at = [&](const Eigen::VectorXd& v) {
    const auto lists = test::unstacked(v, {fx.points.size(), fx.tangents.size()});
    return f(fx.energy(lists[0], lists[1], pressure));
  };
  ASSERT_GT(test::stacked({analytic.points, analytic.tangents}).cwiseAbs().maxCoeff(), 0) << "nothing to check";
  EXPECT_TRUE(test::matches_fd(test::stacked({analytic.points, analytic.tangents}),
                               test::fd_gradient(at, test::stacked({fx.points, fx.tangents}), 1e-7)));
  const test::ScalarFunction in_pressure = [&](const Eigen::VectorXd& p) {
    return f(fx.energy(fx.points, fx.tangents, p[0]));
  };
  EXPECT_TRUE(test::matches_fd(
      analytic.pressure,
      test::central_difference(in_pressure, Eigen::VectorXd::Constant(1, pressure), Eigen::VectorXd::Ones(1), 1.0),
      test::kFdTolerance, 1e-15));
  EXPECT_NE(analytic.pressure, 0);
}

TEST(MuscleParameters, EnergyGradientInPointsTangentsAndPressure)
{
  const Fixture fx;
  for (double p : {50e3, 300e3}) {
    const MuscleEnergy e = fx.energy(fx.points, fx.tangents, p);
    check(fx, e.parameter_gradient(fx.x), p, [&](const MuscleEnergy& m) { return m.value(fx.x); });
  }
}

TEST(MuscleParameters, MixedDerivativeAtRest)
{
  Fixture fx;
  for (Eigen::Index i = 0; i < fx.mesh.nodes.rows(); ++i) fx.x.segment<3>(3 * i) = fx.mesh.nodes.row(i).transpose();
  const MuscleEnergy e = fx.energy(fx.points, fx.tangents, 300e3);
  check(fx, e.mixed_derivative(fx.x, fx.lambda), 300e3, [&](const MuscleEnergy& m) { return fx.phi(m); });
}

TEST(MuscleParameters, MixedDerivativeOfTheForceForTheAdjoint)
{
  const Fixture fx;
  for (double p : {50e3, 300e3}) {
    const MuscleEnergy e = fx.energy(fx.points, fx.tangents, p);
    check(fx, e.mixed_derivative(fx.x, fx.lambda), p, [&](const MuscleEnergy& m) { return fx.phi(m); });
  }
}

TEST(MuscleParameters, MixedColumnsForTheForwardSensitivities)
{
  // M = ∂²E/∂x∂(s, p): Mᵀλ is the adjoint's mixed term for every λ, and a column is the change of
  // the force ∂E/∂x as its parameter moves (central differences).
  const Fixture fx;
  for (double p : {50e3, 300e3}) {
    const MuscleEnergy e = fx.energy(fx.points, fx.tangents, p);
    const Eigen::MatrixXd M = e.mixed_columns(fx.x);
    const FiberParameterGradient g = e.mixed_derivative(fx.x, fx.lambda);
    const Eigen::VectorXd by_columns = M.transpose() * fx.lambda;
    Eigen::VectorXd by_adjoint(M.cols());
    for (std::size_t k = 0; k < fx.points.size(); ++k) {
      by_adjoint.segment<3>(6 * static_cast<Eigen::Index>(k)) = g.points[k];
      by_adjoint.segment<3>(6 * static_cast<Eigen::Index>(k) + 3) = g.tangents[k];
    }
    by_adjoint[M.cols() - 1] = g.pressure;
    EXPECT_LT((by_columns - by_adjoint).norm(), 1e-10 * by_adjoint.norm()) << "p = " << p;
    // Tangent 1's y component and the pressure, against differences of the force.
    const auto force = [&](const MuscleEnergy& m) {
      Eigen::VectorXd f = Eigen::VectorXd::Zero(fx.x.size());
      m.add_gradient(fx.x, f);
      return f;
    };
    std::vector<Eigen::Vector3d> up = fx.tangents, down = fx.tangents;
    const double h = 1e-7;
    up[1].y() += h;
    down[1].y() -= h;
    const Eigen::VectorXd fd = (force(fx.energy(fx.points, up, p)) - force(fx.energy(fx.points, down, p))) / (2 * h);
    EXPECT_LT((M.col(6 + 3 + 1) - fd).norm(), 1e-5 * fd.norm());
    const double hp = 1e-3 * p;
    const Eigen::VectorXd fdp =
        (force(fx.energy(fx.points, fx.tangents, p + hp)) - force(fx.energy(fx.points, fx.tangents, p - hp))) /
        (2 * hp);
    EXPECT_LT((M.col(M.cols() - 1) - fdp).norm(), 1e-5 * fdp.norm());
  }
}

} // namespace
} // namespace fibermold
