#include "sim/energy.hpp"

#include <Eigen/Eigenvalues>

namespace fibermold {

Eigen::MatrixXd project_psd(const Eigen::MatrixXd& A)
{
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(A);
  if (eig.eigenvalues().minCoeff() >= 0) return A;
  return eig.eigenvectors() * eig.eigenvalues().cwiseMax(0).asDiagonal() * eig.eigenvectors().transpose();
}

Eigen::Matrix<double, 9, 9> project_psd(const Eigen::Matrix<double, 9, 9>& A)
{
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 9, 9>> eig(A);
  if (eig.eigenvalues().minCoeff() >= 0) return A;
  return eig.eigenvectors() * eig.eigenvalues().cwiseMax(0).asDiagonal() * eig.eigenvectors().transpose();
}

} // namespace fibermold
