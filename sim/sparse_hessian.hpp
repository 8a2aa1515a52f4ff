#pragma once
// The simulation Hessian: a symmetric matrix of 3×3 node blocks whose sparsity pattern is
// computed once (from every energy's stencils) and whose values are refilled each Newton step.

#include <vector>

#include <Eigen/Sparse>

namespace fibermold {

class SparseHessian {
public:
  /// `stencils`: node sets whose nodes are coupled (every pair gets a block).
  SparseHessian(Eigen::Index num_nodes, const std::vector<std::vector<int>>& stencils);

  Eigen::Index num_nodes() const { return static_cast<Eigen::Index>(neighbours_.size()); }
  const std::vector<int>& neighbours(Eigen::Index j) const { return neighbours_[j]; }

  void set_zero() { matrix_.coeffs().setZero(); }
  /// Adds `block` at node block (i, j). Not thread-safe across the same column j.
  void add_block(int i, int j, const Eigen::Matrix3d& block);
  /// Adds `block` at the k-th neighbour of column j (fast path for parallel assembly per column).
  void add_block_at(int k, int j, const Eigen::Matrix3d& block);
  /// Index of node i among j's neighbours, or -1.
  int position(int i, int j) const;

  /// Full symmetric matrix, column-major, 3n × 3n.
  const Eigen::SparseMatrix<double>& matrix() const { return matrix_; }

private:
  std::vector<std::vector<int>> neighbours_;  ///< sorted, per node column
  std::vector<Eigen::Index> block_start_;
  Eigen::SparseMatrix<double> matrix_;
};

} // namespace fibermold
