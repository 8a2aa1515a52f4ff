#include "sim/shape_functions.hpp"

namespace fibermold {

Eigen::Vector3d ShapeEval::position(const Eigen::VectorXd& x) const
{
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  for (Eigen::Index k = 0; k < size(); ++k) p += N[k] * x.segment<3>(3 * nodes[k]);
  return p;
}

Eigen::Matrix3d ShapeEval::deformation_gradient(const Eigen::VectorXd& x) const
{
  Eigen::Matrix3d F = Eigen::Matrix3d::Zero();
  for (Eigen::Index k = 0; k < size(); ++k) F += x.segment<3>(3 * nodes[k]) * dN.row(k);
  return F;
}

} // namespace fibermold
