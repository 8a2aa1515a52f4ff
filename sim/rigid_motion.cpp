#include "sim/rigid_motion.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>
#include <Eigen/SVD>

namespace fibermold {

double RigidMotion::angle() const { return Eigen::AngleAxisd(rotation).angle(); }

Eigen::Vector3d RigidMotion::axis() const
{
  const Eigen::AngleAxisd a(rotation);
  return a.angle() > 0 ? a.axis() : Eigen::Vector3d::UnitX();
}

double RigidMotion::angle_about(const Eigen::Vector3d& axis) const
{
  // q = (w, v) = swing · twist; the twist about a is (w, (v·a) a) normalised: angle 2 atan2(v·a, w).
  const Eigen::Quaterniond q(rotation);
  const double along = q.vec().dot(axis.normalized());
  double angle = 2 * std::atan2(along, q.w());
  if (angle > M_PI) angle -= 2 * M_PI;
  if (angle < -M_PI) angle += 2 * M_PI;
  return angle;
}

RigidMotion rotation_about(const Eigen::Vector3d& axis, double angle, const Eigen::Vector3d& point,
                           const Eigen::Vector3d& translation)
{
  // x = R (X − p) + p + t
  RigidMotion m;
  m.rotation = Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
  m.translation = point - m.rotation * point + translation;
  return m;
}

Eigen::Vector3d uniform_curl_translation(const Eigen::Vector3d& base, const Eigen::Vector3d& centroid,
                                         const Eigen::Vector3d& axis, double angle)
{
  const Eigen::Vector3d a = axis.normalized(), along = a * a.dot(centroid - base), v = centroid - base - along;
  const double L = v.norm();
  if (angle == 0 || L == 0) return Eigen::Vector3d::Zero();
  const Eigen::Vector3d u = v / L, n = a.cross(u);
  return base + along + L / angle * (std::sin(angle) * u + (1 - std::cos(angle)) * n) - centroid;
}

RigidMotion fitted_rigid_motion(const Eigen::MatrixX3d& rest, const Eigen::MatrixX3d& deformed)
{
  RigidMotion m;
  if (rest.rows() == 0) return m;
  const Eigen::RowVector3d c0 = rest.colwise().mean(), c1 = deformed.colwise().mean();
  // H = Σ (X − X̄)(x − x̄)ᵀ = U Σ Vᵀ; R = V diag(1, 1, det(V Uᵀ)) Uᵀ.
  const Eigen::Matrix3d H = (rest.rowwise() - c0).transpose() * (deformed.rowwise() - c1);
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(H, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::Vector3d sigma = svd.singularValues();
  // Points on one line (or one point) leave the rotation about that line undetermined.
  if (!(sigma(1) > 1e-12 * std::max(sigma(0), 1e-300))) {
    m.translation = (c1 - c0).transpose();
    return m;
  }
  Eigen::Matrix3d D = Eigen::Matrix3d::Identity();
  D(2, 2) = (svd.matrixV() * svd.matrixU().transpose()).determinant() < 0 ? -1 : 1;
  m.rotation = svd.matrixV() * D * svd.matrixU().transpose();
  m.translation = c1.transpose() - m.rotation * c0.transpose();
  return m;
}

Eigen::Matrix3d polar_rotation(const Eigen::Matrix3d& F)
{
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(F, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d D = Eigen::Matrix3d::Identity();
  D(2, 2) = (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0 ? -1 : 1;
  return svd.matrixU() * D * svd.matrixV().transpose();
}

} // namespace fibermold
