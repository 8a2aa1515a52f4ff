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

/// The translation, after a turn by `angle` about unit `axis` through `centroid`, that puts a region's
/// centroid where a uniform curl from `base` takes it: the body between them bends into a circular
/// arc of its length, turning by `angle`. With v = c − b less its part along the axis, L = |v|,
/// û = v/L and n̂ = axis × û (where a positive angle turns û), the centroid goes to
///   b + (a·(c − b)) a + (L/θ)(sin θ û + (1 − cos θ) n̂),
/// so the translation is that less c; 0 when θ = 0 or c lies on the axis through b.
Eigen::Vector3d uniform_curl_translation(const Eigen::Vector3d& base, const Eigen::Vector3d& centroid,
                                         const Eigen::Vector3d& axis, double angle);

/// The rigid motion that takes `rest` (rows) closest to `deformed` in least squares (Kabsch).
/// Needs three points not on one line; fewer determine no rotation, and the identity is used.
RigidMotion fitted_rigid_motion(const Eigen::MatrixX3d& rest, const Eigen::MatrixX3d& deformed);

/// The rotation R of the polar decomposition F = R U: how the material at a point turned.
Eigen::Matrix3d polar_rotation(const Eigen::Matrix3d& F);

} // namespace fibermold
