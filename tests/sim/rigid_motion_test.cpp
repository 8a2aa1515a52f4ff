#include "sim/rigid_motion.hpp"

#include <cmath>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

namespace fibermold {
namespace {

constexpr double kDeg = M_PI / 180;

Eigen::MatrixX3d grid_points()
{
  Eigen::MatrixX3d X(8, 3);
  X << 0, 0, 0, 0.01, 0, 0, 0, 0.02, 0, 0, 0, 0.005, 0.01, 0.02, 0, 0.01, 0, 0.005, 0, 0.02, 0.005, 0.01, 0.02, 0.005;
  return X;
}

TEST(RigidMotion, ARotationAboutAPointKeepsThePointAndTurnsByItsAngle)
{
  const Eigen::Vector3d p(0.05, 0.01, 0), t(0.002, 0, -0.001);
  const RigidMotion m = rotation_about({0, 0, 2}, 60 * kDeg, p, t);
  EXPECT_LT((m.apply(p) - (p + t)).norm(), 1e-15);
  EXPECT_NEAR(m.angle(), 60 * kDeg, 1e-12);
  EXPECT_LT((m.axis() - Eigen::Vector3d::UnitZ()).norm(), 1e-12);
  EXPECT_NEAR(m.angle_about({0, 0, 1}), 60 * kDeg, 1e-12);
  EXPECT_NEAR(m.angle_about({0, 0, -1}), -60 * kDeg, 1e-12);
}

TEST(RigidMotion, TheFitRecoversAMotionFromItsPointsAndTheTwistIgnoresASwing)
{
  const Eigen::MatrixX3d X = grid_points();
  const Eigen::Matrix3d R =
      (Eigen::AngleAxisd(40 * kDeg, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(5 * kDeg, Eigen::Vector3d::UnitX()))
          .toRotationMatrix();
  const Eigen::Vector3d t(0.01, -0.02, 0.003);
  const Eigen::MatrixX3d x = ((X * R.transpose()).rowwise() + t.transpose()).eval();
  const RigidMotion m = fitted_rigid_motion(X, x);
  EXPECT_LT((m.rotation - R).norm(), 1e-12);
  EXPECT_LT((m.translation - t).norm(), 1e-14);
  // Twist about z of swing(x, 5°) · twist(z, 40°)... composed the other way round: within 0.1°.
  EXPECT_NEAR(m.angle_about({0, 0, 1}) / kDeg, 40, 0.1);
  EXPECT_GT(m.angle() / kDeg, 40); // the swing adds to the whole angle
}

TEST(RigidMotion, TooFewPointsForARotationGiveOnlyTheTranslation)
{
  Eigen::MatrixX3d X(2, 3), x(2, 3);
  X << 0, 0, 0, 0.01, 0, 0;
  x << 0, 0.001, 0, 0.01, 0.001, 0;
  const RigidMotion m = fitted_rigid_motion(X, x);
  EXPECT_EQ(m.angle(), 0);
  EXPECT_LT((m.translation - Eigen::Vector3d(0, 0.001, 0)).norm(), 1e-15);
}

TEST(RigidMotion, ThePolarRotationOfAStretchedTurnIsTheTurn)
{
  const Eigen::Matrix3d R = Eigen::AngleAxisd(25 * kDeg, Eigen::Vector3d(1, 1, 0).normalized()).toRotationMatrix();
  const Eigen::Matrix3d U = Eigen::Vector3d(1.2, 0.9, 1.05).asDiagonal();
  EXPECT_LT((polar_rotation(R * U) - R).norm(), 1e-12);
}

/// A finger along +x curling uniformly: its end goes to (L/θ)(sin θ, 1 − cos θ) along the finger
/// and toward where the angle turns it (docs/targets.md's worked figures), an offset along the axis
/// is carried along, and no angle moves nothing.
TEST(RigidMotion, AUniformCurlMovesTheEndAlongTheArc)
{
  const Eigen::Vector3d base(0, 0, 0);
  // 100 mm, 60° about +z: toward +y.
  Eigen::Vector3d t = uniform_curl_translation(base, {0.1, 0, 0}, {0, 0, 1}, M_PI / 3);
  EXPECT_NEAR(t.x() * 1e3, -17.30, 0.005);
  EXPECT_NEAR(t.y() * 1e3, 47.75, 0.005);
  EXPECT_NEAR(t.z(), 0, 1e-15);
  // 90 mm, 45° about +y: +x turns toward −z.
  t = uniform_curl_translation(base, {0.09, 0, 0}, {0, 2, 0}, M_PI / 4);
  EXPECT_NEAR(t.x() * 1e3, -8.97, 0.005);
  EXPECT_NEAR(t.y(), 0, 1e-15);
  EXPECT_NEAR(t.z() * 1e3, -33.56, 0.005);
  // The base off the finger's line along the axis, and the finger elsewhere: the same curl.
  const Eigen::Vector3d shift(0.01, -0.02, 0.03);
  const Eigen::Vector3d u = uniform_curl_translation(shift + Eigen::Vector3d(0, 0, -0.004),
                                                     shift + Eigen::Vector3d(0.1, 0, 0), {0, 0, 1}, M_PI / 3);
  EXPECT_NEAR((u - uniform_curl_translation(base, {0.1, 0, 0}, {0, 0, 1}, M_PI / 3)).norm(), 0, 1e-15);
  // Half a turn: the end comes back over the base, 2L/π to the side, facing back.
  t = uniform_curl_translation(base, {0.1, 0, 0}, {0, 0, 1}, M_PI);
  EXPECT_NEAR(t.x(), -0.1, 1e-15);
  EXPECT_NEAR(t.y(), 0.2 / M_PI, 1e-15);
  EXPECT_EQ(uniform_curl_translation(base, {0.1, 0, 0}, {0, 0, 1}, 0), Eigen::Vector3d::Zero());
}

} // namespace
} // namespace fibermold
