#include "sim/external_forces.hpp"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

namespace fibermold {
namespace {

TEST(ExternalForces, RegionForceAndTorqueHaveTheirTotals)
{
  Eigen::MatrixX3d X(5, 3);
  X << 0, 0, 0, 0.01, 0, 0, 0, 0.01, 0, 0, 0, 0.01, 0.01, 0.01, 0.01;
  const Eigen::VectorXd w = (Eigen::VectorXd(5) << 1, 2, 3, 4, 5).finished();
  const std::vector<int> nodes{0, 1, 2, 3, 4};
  const Eigen::Vector3d F(1, -2, 3), T(0.01, 0.02, -0.03);
  const Eigen::VectorXd f = region_force(nodes, w, X, F);
  Eigen::Vector3d total = Eigen::Vector3d::Zero();
  for (int i : nodes) total += f.segment<3>(3 * i);
  EXPECT_LT((total - F).norm(), 1e-15);

  const Eigen::VectorXd t = region_torque(nodes, w, X, T);
  Eigen::Vector3d sum = Eigen::Vector3d::Zero(), moment = Eigen::Vector3d::Zero();
  for (int i : nodes) {
    sum += t.segment<3>(3 * i);
    moment += Eigen::Vector3d(X.row(i)).cross(Eigen::Vector3d(t.segment<3>(3 * i)));
  }
  EXPECT_LT(sum.norm(), 1e-12);
  EXPECT_LT((moment - T).norm(), 1e-12); // about any point, as Σ f = 0

  EXPECT_THROW(region_torque({0, 1}, w, X, T), std::invalid_argument);
  Eigen::MatrixX3d line(3, 3);
  line << 0, 0, 0, 0.01, 0, 0, 0.02, 0, 0;
  EXPECT_THROW(region_torque({0, 1, 2}, w, line, T), std::invalid_argument);
}

} // namespace
} // namespace fibermold
