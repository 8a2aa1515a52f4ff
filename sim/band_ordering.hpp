#pragma once
// A band (profile) ordering of a symmetric sparse matrix: reverse Cuthill–McKee (Cuthill & McKee
// 1969; George 1971), from Boost.Graph. On a long body whose Hessian couples each node with every
// node within a few edge lengths, it numbers the nodes along the body, and the Cholesky factor of
// the reordered matrix is a band about one cross-section's couplings wide: fewer operations than
// minimum degree finds there (the gripper finger at 3.4 mm: 12.4 Gflop against AMD's 18.9), in
// large dense supernodes that BLAS runs fast. cholmod_solver.cpp compares the two per pattern.

#include <vector>

#include <Eigen/Sparse>

namespace fibermold {

/// The band ordering of the symmetric matrix whose upper triangle is `upper` (its pattern only):
/// order[k] is the row placed k-th. The graph's components are ordered one after the other.
std::vector<int> band_ordering(const Eigen::SparseMatrix<double>& upper);

} // namespace fibermold
