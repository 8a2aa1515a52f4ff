#include "sim/point_forces.hpp"

#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "sim/stiffness_column.hpp"

namespace fibermold {
namespace {

struct Point {
  std::vector<int> nodes{0, 2, 3, 6}; // ascending, with gaps; node 6 is x's last: a 4-wide read would overrun
  std::vector<Eigen::Vector3d> dN;
  Eigen::VectorXd x = Eigen::VectorXd::Zero(21);
};

Point random_point(std::mt19937& rng)
{
  std::uniform_real_distribution<double> u(-1, 1);
  Point p;
  for (std::size_t k = 0; k < p.nodes.size(); ++k) p.dN.emplace_back(u(rng), u(rng), u(rng));
  for (Eigen::Index i = 0; i < p.x.size(); ++i) p.x[i] = u(rng);
  return p;
}

TEST(PointForces, BothKernelsGatherTheDeformationGradient)
{
  std::mt19937 rng(3);
  const Point p = random_point(rng);
  Eigen::Matrix3d expected = Eigen::Matrix3d::Zero();
  for (std::size_t k = 0; k < p.nodes.size(); ++k) expected += p.x.segment<3>(3 * p.nodes[k]) * p.dN[k].transpose();
  for (const bool simd : {false, true}) {
    SCOPED_TRACE(simd ? "AVX2" : "portable");
    if (simd && !stiffness_simd_available()) GTEST_SKIP() << "no AVX2 and FMA on this processor";
    // Odd and even counts: the AVX2 kernel takes entries in pairs.
    for (int count : {4, 3, 1}) {
      Eigen::Matrix3d partial = Eigen::Matrix3d::Zero();
      for (int k = 0; k < count; ++k) partial += p.x.segment<3>(3 * p.nodes[k]) * p.dN[k].transpose();
      const Eigen::Matrix3d F = gather_deformation_gradient(p.x.data(), p.nodes.data(), p.dN.data(), count, simd);
      EXPECT_LT((F - partial).cwiseAbs().maxCoeff(), 1e-15) << count << " entries";
    }
  }
}

TEST(PointForces, BothKernelsAddTheNodalForcesAndTouchNoOtherNode)
{
  std::mt19937 rng(5);
  const Point p = random_point(rng);
  std::uniform_real_distribution<double> u(-1, 1);
  Eigen::Matrix3d VP;
  for (int a = 0; a < 3; ++a)
    for (int c = 0; c < 3; ++c) VP(a, c) = u(rng);
  for (const bool simd : {false, true}) {
    SCOPED_TRACE(simd ? "AVX2" : "portable");
    if (simd && !stiffness_simd_available()) GTEST_SKIP() << "no AVX2 and FMA on this processor";
    Eigen::VectorXd g = Eigen::VectorXd::Constant(21, 0.5);
    scatter_point_forces(VP, p.nodes.data(), p.dN.data(), 4, g.data(), simd);
    Eigen::VectorXd expected = Eigen::VectorXd::Constant(21, 0.5);
    for (std::size_t k = 0; k < p.nodes.size(); ++k) expected.segment<3>(3 * p.nodes[k]) += VP * p.dN[k];
    EXPECT_LT((g - expected).cwiseAbs().maxCoeff(), 1e-15);
    for (int untouched : {1, 4, 5})
      EXPECT_EQ(g.segment<3>(3 * untouched), Eigen::Vector3d::Constant(0.5)) << "node " << untouched;
  }
}

} // namespace
} // namespace fibermold
