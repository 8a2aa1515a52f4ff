// MLS and FEM shape functions: reproduction (patch) properties and exact derivatives.
#include <random>

#include <gtest/gtest.h>

#include "finite_differences.hpp"
#include "mesh/mesh_quality.hpp"
#include "sim/fem_basis.hpp"
#include "sim/mls_basis.hpp"
#include "sim_fixtures.hpp"

namespace fibermold {
namespace {

struct BasisSetup {
  TetMesh mesh;
  std::unique_ptr<Basis> basis;
  int degree; ///< polynomial degree reproduced exactly
};

BasisSetup make(const std::string& kind)
{
  BasisSetup s;
  s.mesh = test::box_mesh({0, 0, 0}, {0.03, 0.02, 0.02}, 0.005, kind == "fem-p2");
  const double h = mesh_quality(s.mesh).mean_edge_length;
  if (kind == "fem-p1" || kind == "fem-p2") {
    s.basis = std::make_unique<FemBasis>(s.mesh);
    s.degree = kind == "fem-p2" ? 2 : 1;
  } else {
    MlsOptions o;
    o.quadratic = kind == "mls-quadratic";
    o.radius = (o.quadratic ? 2.5 : 1.7) * h;
    s.basis = std::make_unique<MlsBasis>(s.mesh.nodes, o);
    s.degree = o.quadratic ? 2 : 1;
  }
  return s;
}

std::vector<Eigen::Vector3d> random_points(int count, unsigned seed)
{
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> u(0.002, 0.018);
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < count; ++i) points.emplace_back(0.03 / 0.02 * u(random), u(random), u(random));
  return points;
}

class ShapeFunctions : public ::testing::TestWithParam<std::string> {};

TEST_P(ShapeFunctions, ReproducePolynomialsOfTheirDegreeExactly)
{
  const BasisSetup s = make(GetParam());
  const Eigen::Matrix3d A = (Eigen::Matrix3d() << 1.1, 0.2, -0.1, 0.05, 0.9, 0.3, -0.2, 0.1, 1.2).finished();
  const Eigen::Vector3d b(0.01, -0.02, 0.005);
  // q(X) = A X + b + degree-2 term c (X·e)²
  const Eigen::Vector3d c = s.degree == 2 ? Eigen::Vector3d(3, -2, 1) : Eigen::Vector3d::Zero();
  const Eigen::Vector3d e(0.3, 0.5, -0.8);
  const auto field = [&](const Eigen::Vector3d& X) -> Eigen::Vector3d { return A * X + b + c * std::pow(X.dot(e), 2); };
  Eigen::VectorXd x(3 * s.mesh.nodes.rows());
  for (Eigen::Index i = 0; i < s.mesh.nodes.rows(); ++i) x.segment<3>(3 * i) = field(s.mesh.nodes.row(i).transpose());
  for (const Eigen::Vector3d& X : random_points(50, 3)) {
    const ShapeEval f = s.basis->at(X, 2);
    EXPECT_NEAR(f.N.sum(), 1.0, 1e-12);
    EXPECT_LT((f.position(x) - field(X)).norm(), 1e-10 * 0.03);
    const Eigen::Matrix3d F = A + 2 * c * X.dot(e) * e.transpose();
    EXPECT_LT((f.deformation_gradient(x) - F).norm(), 1e-9);
    Eigen::Matrix3d second_sum = Eigen::Matrix3d::Zero(); // Σ_i x_i,0 ∇∇N_i = ∇∇q_0
    for (Eigen::Index k = 0; k < f.size(); ++k) second_sum += x[3 * f.nodes[k]] * f.ddN[k];
    EXPECT_LT((second_sum - 2 * c[0] * e * e.transpose()).norm(), 1e-6);
  }
}

TEST_P(ShapeFunctions, DerivativesMatchFiniteDifferences)
{
  const BasisSetup s = make(GetParam());
  const double h = 1e-7;
  for (const Eigen::Vector3d& X : random_points(20, 5)) {
    const ShapeEval f = s.basis->at(X, 2);
    const Eigen::Index tet = GetParam().starts_with("fem") ? dynamic_cast<const FemBasis&>(*s.basis).locate(X) : -1;
    for (int k = 0; k < 3; ++k)
      for (int side : {-1, 1})
        ASSERT_EQ(s.basis->at(X + side * h * Eigen::Vector3d::Unit(k), 1, tet).nodes, f.nodes)
            << "support changed within the step";
    // N and ∇N as functions of X, each node's entries in a row.
    const test::VectorFunction N = [&](const Eigen::VectorXd& Y) { return Eigen::VectorXd(s.basis->at(Y, 1, tet).N); };
    const test::VectorFunction dN = [&](const Eigen::VectorXd& Y) {
      return Eigen::VectorXd(s.basis->at(Y, 1, tet).dN.reshaped<Eigen::RowMajor>());
    };
    const Eigen::VectorXd at = X;
    ASSERT_GT(f.dN.cwiseAbs().maxCoeff(), 0);
    EXPECT_TRUE(test::matches_fd(f.dN, test::fd_jacobian(N, at, h)));
    if (s.degree == 2 || GetParam().starts_with("mls")) {
      Eigen::MatrixXd ddN(3 * f.size(), 3); // row 3 i + a: ∂²N_i / ∂X_a ∂X_k in column k
      for (Eigen::Index i = 0; i < f.size(); ++i) ddN.middleRows(3 * i, 3) = f.ddN[i];
      ASSERT_GT(ddN.cwiseAbs().maxCoeff(), 0);
      EXPECT_TRUE(test::matches_fd(ddN, test::fd_jacobian(dN, at, h)));
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Bases, ShapeFunctions, ::testing::Values("mls-linear", "mls-quadratic", "fem-p1", "fem-p2"));

TEST(FemBasis, LocatesAPointInALargeTetBesideManySmallOnes)
{
  // A large tet with X near one corner, and 40 small tets just outside it whose centroids lie
  // nearer X than the large tet's (found on a cylinder's mesh: the tet holding a point of the axis
  // was the 34th by centroid distance).
  TetMesh mesh;
  std::vector<Eigen::Vector3d> nodes{{0, 0, 0}, {0.1, 0, 0}, {0, 0.1, 0}, {0, 0, 0.1}};
  std::vector<Eigen::Vector4i> tets{{0, 1, 2, 3}};
  for (int k = 0; k < 40; ++k) {
    const Eigen::Vector3d o(-0.004, 0.001 * (k % 8), 0.001 * (k / 8));
    const int n = static_cast<int>(nodes.size());
    for (const Eigen::Vector3d& e : {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0.001, 0, 0),
                                     Eigen::Vector3d(0, 0.001, 0), Eigen::Vector3d(0, 0, 0.001)})
      nodes.push_back(o + e);
    tets.emplace_back(n, n + 1, n + 2, n + 3);
  }
  mesh.nodes.resize(static_cast<Eigen::Index>(nodes.size()), 3);
  for (std::size_t i = 0; i < nodes.size(); ++i) mesh.nodes.row(static_cast<Eigen::Index>(i)) = nodes[i];
  mesh.tets.resize(static_cast<Eigen::Index>(tets.size()), 4);
  for (std::size_t t = 0; t < tets.size(); ++t) mesh.tets.row(static_cast<Eigen::Index>(t)) = tets[t];
  const FemBasis basis(mesh);
  const Eigen::Vector3d X(0.001, 0.002, 0.002);
  EXPECT_EQ(basis.locate(X), 0);
  EXPECT_GE(basis.barycentric(basis.locate(X), X).minCoeff(), 0.0);
  const Eigen::Vector3d outside(-0.01, 0.002, 0.002); // outside every tet: the least-outside one
  EXPECT_LT(basis.barycentric(basis.locate(outside), outside).minCoeff(), 0.0);
}

TEST(MlsBasis, SmoothAcrossTheSupportBoundary)
{
  // Walk a node out of the support: its N, ∇N and ∇∇N go to zero continuously (C³ weight).
  const BasisSetup s = make("mls-linear");
  const auto& mls = dynamic_cast<const MlsBasis&>(*s.basis);
  const Eigen::Vector3d node = s.mesh.nodes.row(s.mesh.nodes.rows() / 2).transpose();
  const Eigen::Vector3d direction = Eigen::Vector3d(1, 0.3, -0.2).normalized();
  const double r = mls.radius();
  // Just inside: N ~ (1 − s)⁴, ∇N ~ (1 − s)³/r, ∇∇N ~ (1 − s)²/r² with 1 − s ≈ 1e-5.
  const ShapeEval inside = mls.at(node + (r - 1e-7) * direction, 2);
  int found = 0;
  for (Eigen::Index k = 0; k < inside.size(); ++k)
    if (inside.nodes[k] == s.mesh.nodes.rows() / 2) {
      ++found;
      EXPECT_LT(std::abs(inside.N[k]), 1e-15);
      EXPECT_LT(inside.dN.row(k).norm(), 1e-8);
      EXPECT_LT(inside.ddN[k].norm(), 1e-5 / (r * r)); // typical |∇∇N| ~ 1/r²
    }
  EXPECT_EQ(found, 1);
  const ShapeEval outside = mls.at(node + (r + 1e-7) * direction, 2);
  for (int n : outside.nodes) EXPECT_NE(n, s.mesh.nodes.rows() / 2);
}

TEST(MlsBasis, TooFewNodesWidenTheRadiusAndNeverReturnNaN)
{
  const BasisSetup s = make("mls-quadratic");
  MlsOptions o;
  o.quadratic = true;
  o.radius = 0.4 * mesh_quality(s.mesh).mean_edge_length; // far too small for 10 monomials
  const MlsBasis tight(s.mesh.nodes, o);
  const ShapeEval f = tight.at(Eigen::Vector3d(0.011, 0.009, 0.012), 2);
  EXPECT_TRUE(f.N.allFinite());
  EXPECT_TRUE(f.dN.allFinite());
  EXPECT_NEAR(f.N.sum(), 1.0, 1e-10);
  EXPECT_GE(tight.conditioning().widened, 1u);
  o.max_widenings = 0;
  const MlsBasis refusing(s.mesh.nodes, o);
  EXPECT_THROW(refusing.at(Eigen::Vector3d(0.011, 0.009, 0.012), 1), std::runtime_error);
}

} // namespace
} // namespace fibermold
