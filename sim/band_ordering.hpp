#pragma once
// A band (profile) ordering of a symmetric sparse matrix: Sloan's (Sloan 1986), from Boost.Graph,
// on the graph of nodes. On a long body whose Hessian couples each node with every node within a
// few edge lengths, it numbers the nodes along the body from one end to the other, and the
// Cholesky factor of the reordered matrix is a band about one cross-section's couplings wide:
// fewer operations than minimum degree finds there (the gripper finger at 3.4 mm: 10.6 Gflop
// against AMD's 18.9 and reverse Cuthill–McKee's 12.4), in large dense supernodes that BLAS runs
// fast. Within the band, Sloan's priority numbers next the node that adds least to the front of
// active rows. cholmod_solver.cpp compares it with CHOLMOD's own per pattern.

#include <vector>

#include <Eigen/Sparse>

namespace fibermold {

/// The band ordering of the symmetric matrix whose upper triangle is `upper` (its pattern only):
/// order[k] is the row placed k-th. The graph's components are ordered one after the other.
std::vector<int> band_ordering(const Eigen::SparseMatrix<double>& upper);

} // namespace fibermold
