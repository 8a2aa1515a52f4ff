#pragma once
// Sparse Cholesky (CHOLMOD supernodal) behind one small class: the symbolic analysis is computed
// once and reused while the sparsity pattern stays the same (after geometry-central and ceres).

#include <memory>

#include <Eigen/Sparse>

namespace fibermold {

class CholmodSolver {
public:
  CholmodSolver();
  ~CholmodSolver();
  CholmodSolver(const CholmodSolver&) = delete;
  CholmodSolver& operator=(const CholmodSolver&) = delete;

  /// Factorizes A + shift·I (A symmetric; its upper triangle is read, each column's rows ascending
  /// as CHOLMOD takes them from Eigen).
  /// Analyzes the pattern on the first call and whenever A's pattern differs from the last one.
  /// Returns false when A + shift·I is not positive definite.
  bool factorize(const Eigen::SparseMatrix<double>& A, double shift = 0);
  Eigen::VectorXd solve(const Eigen::VectorXd& b) const;
  /// All of B's columns in one pass (a block back-substitution).
  Eigen::MatrixXd solve(const Eigen::MatrixXd& B) const;

  int analyses() const { return analyses_; }
  /// The floating-point operations of one factorization of the pattern last analyzed (CHOLMOD's
  /// count), which sets the BLAS threads it runs on (cholmod_solver.cpp, kTwoThreadFlops).
  double flops() const;
  /// Whether the pattern last analyzed is factorized in the band ordering (band_ordering.hpp).
  bool band_ordered() const;

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  int analyses_ = 0;
};

} // namespace fibermold
