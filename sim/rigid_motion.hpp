#pragma once
// Rigid motions x ↦ R X + t: the pose a target asks of a region, and the pose a deformed region or
// point has reached (the rotation and translation that best explain its displacement).

#include <Eigen/Core>

namespace fibermold {

struct RigidMotion {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero(); ///< m

  Eigen::Vector3d apply(const Eigen::Vector3d& X) const { return rotation * X + translation; }
  /// The rotation's angle in [0, π] (rad) and its unit axis ((1, 0, 0) when the angle is 0).
  double angle() const;
  Eigen::Vector3d axis() const;
  /// The signed angle (rad) of the rotation's twist about unit `axis` (swing–twist decomposition):
  /// what a rotation "about z" reached when it also swung a little about x or y.
  double angle_about(const Eigen::Vector3d& axis) const;
};

/// Rotation by `angle` (rad) about the line through `point` along `axis` (any length > 0), then `translation`.
RigidMotion rotation_about(const Eigen::Vector3d& axis, double angle, const Eigen::Vector3d& point,
                           const Eigen::Vector3d& translation);

/// The rigid motion that takes `rest` (rows) closest to `deformed` in least squares (Kabsch).
/// Needs three points not on one line; fewer determine no rotation, and the identity is used.
RigidMotion fitted_rigid_motion(const Eigen::MatrixX3d& rest, const Eigen::MatrixX3d& deformed);

/// The rotation R of the polar decomposition F = R U: how the material at a point turned.
Eigen::Matrix3d polar_rotation(const Eigen::Matrix3d& F);

} // namespace fibermold
