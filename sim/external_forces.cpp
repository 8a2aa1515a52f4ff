#include "sim/external_forces.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/LU>
#include <stdexcept>

namespace fibermold {

Eigen::VectorXd nodal_masses(const QuadraturePoints& qp, Eigen::Index num_nodes, double density)
{
  Eigen::VectorXd m = Eigen::VectorXd::Zero(num_nodes);
  for (Eigen::Index q = 0; q < qp.size(); ++q)
    for (int k = qp.offset[q]; k < qp.offset[q + 1]; ++k) m[qp.node[k]] += qp.volume[q] * density * qp.N[k];
  return m;
}

Eigen::VectorXd nodal_volumes(const QuadraturePoints& qp, Eigen::Index num_nodes)
{
  Eigen::VectorXd w = Eigen::VectorXd::Zero(num_nodes);
  for (Eigen::Index q = 0; q < qp.size(); ++q)
    for (int k = qp.offset[q]; k < qp.offset[q + 1]; ++k) w[qp.node[k]] += qp.volume[q] * std::abs(qp.N[k]);
  return w;
}

Eigen::VectorXd gravity_forces(const Eigen::VectorXd& masses, const Eigen::Vector3d& g)
{
  Eigen::VectorXd f(3 * masses.size());
  for (Eigen::Index i = 0; i < masses.size(); ++i) f.segment<3>(3 * i) = masses[i] * g;
  return f;
}

Eigen::VectorXd region_force(const std::vector<int>& nodes, const Eigen::VectorXd& masses, const Eigen::MatrixX3d& X,
                             const Eigen::Vector3d& force)
{
  Eigen::VectorXd f = Eigen::VectorXd::Zero(3 * X.rows());
  double total = 0;
  for (int i : nodes) total += masses[i];
  for (int i : nodes) f.segment<3>(3 * i) = masses[i] / total * force;
  return f;
}

Eigen::VectorXd region_torque(const std::vector<int>& nodes, const Eigen::VectorXd& masses, const Eigen::MatrixX3d& X,
                              const Eigen::Vector3d& torque)
{
  double total = 0;
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (int i : nodes) {
    total += masses[i];
    c += masses[i] * X.row(i).transpose();
  }
  c /= total;
  Eigen::Matrix3d J = Eigen::Matrix3d::Zero();
  for (int i : nodes) {
    const Eigen::Vector3d r = X.row(i).transpose() - c;
    J += masses[i] * (r.squaredNorm() * Eigen::Matrix3d::Identity() - r * r.transpose());
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(J);
  if (nodes.size() < 3 || !(eig.eigenvalues().minCoeff() > 1e-9 * eig.eigenvalues().maxCoeff()))
    throw std::invalid_argument("a torque needs at least 3 nodes that are not on one line");
  const Eigen::Vector3d omega = J.inverse() * torque;
  Eigen::VectorXd f = Eigen::VectorXd::Zero(3 * X.rows());
  for (int i : nodes) f.segment<3>(3 * i) = masses[i] * omega.cross(X.row(i).transpose() - c);
  return f;
}

Eigen::VectorXd point_force(const ShapeEval& at_point, Eigen::Index num_nodes, const Eigen::Vector3d& force)
{
  Eigen::VectorXd f = Eigen::VectorXd::Zero(3 * num_nodes);
  for (Eigen::Index k = 0; k < at_point.size(); ++k) f.segment<3>(3 * at_point.nodes[k]) += at_point.N[k] * force;
  return f;
}

std::vector<int> nodes_in_box(const Eigen::MatrixX3d& X, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi)
{
  const Eigen::Vector3d slack = 1e-9 * (hi - lo).cwiseAbs();
  std::vector<int> nodes;
  for (Eigen::Index i = 0; i < X.rows(); ++i) {
    const Eigen::Vector3d p = X.row(i).transpose();
    if (((p - lo).array() >= -slack.array()).all() && ((hi - p).array() >= -slack.array()).all())
      nodes.push_back(static_cast<int>(i));
  }
  return nodes;
}

} // namespace fibermold
