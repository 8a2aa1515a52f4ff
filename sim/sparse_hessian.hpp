#pragma once
// The simulation Hessian: a symmetric matrix of 3×3 node blocks whose sparsity pattern is
// computed once (from every energy's stencils) and whose values are refilled each Newton step.
// Only the blocks (i, j) with i ≤ j are stored (the upper block triangle, diagonal blocks whole):
// half the assembly work and memory. CHOLMOD reads the upper triangle: from the lower one it
// transposes the matrix twice per factorization, from the upper one once (0.035–0.044 →
// 0.030–0.032 s per factorization of the twisting bar at the paper's tet count).

#include <vector>

#include <Eigen/Sparse>

namespace fibermold {

class SparseHessian {
public:
  /// `stencils`: node sets whose nodes are coupled (every pair gets a block).
  SparseHessian(Eigen::Index num_nodes, const std::vector<std::vector<int>>& stencils);
  /// `base`'s pattern grown by the pairs of `stencils` (values zero).
  SparseHessian(const SparseHessian& base, const std::vector<std::vector<int>>& stencils);

  /// Whether every pair of every stencil has a block.
  bool contains(const std::vector<std::vector<int>>& stencils) const;

  Eigen::Index num_nodes() const { return static_cast<Eigen::Index>(neighbours_.size()); }
  const std::vector<int>& neighbours(Eigen::Index j) const { return neighbours_[j]; }

  void set_zero()
  {
    matrix_.coeffs().setZero();
    lumped_ = 0;
  }
  /// Adds `block` at node block (i, j) when i ≤ j; the caller adds (j, i) too, which is dropped.
  /// Not thread-safe across the same column j.
  void add_block(int i, int j, const Eigen::Matrix3d& block);
  /// Adds c·M at blocks (a, b) and (b, a), a ≠ b, for a symmetric 3×3 M. Where the pattern lacks
  /// the pair it adds |c|·M to blocks (a, a) and (b, b) instead (diagonal compensation: with M
  /// positive semi-definite the matrix stays so) and counts the pair in lumped().
  void add_coupling(int a, int b, double c, const Eigen::Matrix3d& M);
  /// Pairs added on the diagonal by add_coupling since set_zero(): the matrix is then an
  /// approximation of the one a pattern with those pairs would hold.
  int lumped() const { return lumped_; }
  /// Adds `block` at the k-th stored neighbour (i ≤ j) of column j (fast path for parallel assembly).
  void add_block_at(int k, int j, const Eigen::Matrix3d& block);
  /// The values of node column j: 3 scalar columns of 3·|neighbours(j)| rows each, one after the
  /// other; block (k-th neighbour, j) entry (a, b) is at [3·|neighbours(j)|·b + 3k + a].
  double* column_values(Eigen::Index j) { return matrix_.valuePtr() + 9 * block_start_[j]; }
  /// Index of node i among j's stored neighbours (i ≤ j), or -1.
  int position(int i, int j) const;

  /// The upper triangle (whole diagonal blocks), column-major, 3n × 3n.
  const Eigen::SparseMatrix<double>& matrix() const { return matrix_; }
  /// The whole symmetric matrix (for tests and diagnostics).
  Eigen::SparseMatrix<double> full() const;

private:
  void build_matrix();

  std::vector<std::vector<int>> neighbours_; ///< sorted, per node column
  std::vector<Eigen::Index> block_start_;
  Eigen::SparseMatrix<double> matrix_;
  int lumped_ = 0;
};

} // namespace fibermold
