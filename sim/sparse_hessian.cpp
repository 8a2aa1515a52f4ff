#include "sim/sparse_hessian.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace fibermold {

SparseHessian::SparseHessian(Eigen::Index num_nodes, const std::vector<std::vector<int>>& stencils)
    : neighbours_(static_cast<std::size_t>(num_nodes))
{
  // Node → stencils incidence (CSR), then each node's neighbours by marking: memory O(nnz), not
  // O(Σ |stencil|²) as appending every stencil to every node's list would take.
  std::vector<int> offset(static_cast<std::size_t>(num_nodes) + 1, 0);
  for (const auto& s : stencils)
    for (int j : s) ++offset[j + 1];
  for (std::size_t j = 1; j < offset.size(); ++j) offset[j] += offset[j - 1];
  std::vector<int> containing(static_cast<std::size_t>(offset.back()));
  std::vector<int> fill(offset.begin(), offset.end() - 1);
  for (std::size_t s = 0; s < stencils.size(); ++s)
    for (int j : stencils[s]) containing[fill[j]++] = static_cast<int>(s);
  std::vector<int> mark(static_cast<std::size_t>(num_nodes), -1);
  for (Eigen::Index j = 0; j < num_nodes; ++j) {
    auto& nb = neighbours_[j];
    nb.push_back(static_cast<int>(j));
    mark[j] = static_cast<int>(j);
    for (int k = offset[j]; k < offset[j + 1]; ++k)
      for (int i : stencils[containing[k]])
        if (i < j && mark[i] != j) {
          mark[i] = static_cast<int>(j);
          nb.push_back(i);
        }
    std::sort(nb.begin(), nb.end());
  }
  build_matrix();
}

SparseHessian::SparseHessian(const SparseHessian& base, const std::vector<std::vector<int>>& stencils)
    : neighbours_(base.neighbours_)
{
  for (const auto& s : stencils)
    for (int a : s)
      for (int b : s)
        if (a < b) neighbours_[b].push_back(a);
  for (auto& nb : neighbours_) {
    std::sort(nb.begin(), nb.end());
    nb.erase(std::unique(nb.begin(), nb.end()), nb.end());
  }
  build_matrix();
}

bool SparseHessian::contains(const std::vector<std::vector<int>>& stencils) const
{
  for (const auto& s : stencils)
    for (int a : s)
      for (int b : s)
        if (a <= b && position(a, b) < 0) return false;
  return true;
}

void SparseHessian::build_matrix()
{
  const auto num_nodes = static_cast<Eigen::Index>(neighbours_.size());
  block_start_.assign(static_cast<std::size_t>(num_nodes) + 1, 0);
  for (Eigen::Index j = 0; j < num_nodes; ++j)
    block_start_[j + 1] = block_start_[j] + static_cast<Eigen::Index>(neighbours_[j].size());
  // Column 3j + b holds rows 3i + a for i in neighbours(j), a = 0..2.
  const Eigen::Index n = 3 * num_nodes;
  matrix_.resize(n, n);
  matrix_.resizeNonZeros(9 * block_start_.back());
  int* outer = matrix_.outerIndexPtr();
  int* inner = matrix_.innerIndexPtr();
  for (Eigen::Index j = 0; j < num_nodes; ++j) {
    const auto L = static_cast<Eigen::Index>(neighbours_[j].size());
    for (int b = 0; b < 3; ++b) {
      const Eigen::Index start = 9 * block_start_[j] + 3 * L * b;
      outer[3 * j + b] = static_cast<int>(start);
      for (Eigen::Index k = 0; k < L; ++k)
        for (int a = 0; a < 3; ++a) inner[start + 3 * k + a] = 3 * neighbours_[j][k] + a;
    }
  }
  outer[n] = static_cast<int>(9 * block_start_.back());
  matrix_.coeffs().setZero();
}

int SparseHessian::position(int i, int j) const
{
  const auto& nb = neighbours_[j];
  const auto it = std::lower_bound(nb.begin(), nb.end(), i);
  return it != nb.end() && *it == i ? static_cast<int>(it - nb.begin()) : -1;
}

void SparseHessian::add_block_at(int k, int j, const Eigen::Matrix3d& block)
{
  const Eigen::Index L = static_cast<Eigen::Index>(neighbours_[j].size());
  double* values = matrix_.valuePtr();
  for (int b = 0; b < 3; ++b) {
    double* column = values + 9 * block_start_[j] + 3 * L * b + 3 * k;
    for (int a = 0; a < 3; ++a) column[a] += block(a, b);
  }
}

void SparseHessian::add_coupling(int a, int b, double c, const Eigen::Matrix3d& M)
{
  const int i = std::min(a, b), j = std::max(a, b);
  if (const int k = position(i, j); k >= 0) {
    add_block_at(k, j, c * M);
    return;
  }
  // [[|c| M, c M], [c M, |c| M]] is positive semi-definite: dropping the coupling and adding its
  // diagonal part keeps the sum so (the fill-free approximation of the pair).
  add_block_at(position(a, a), a, std::abs(c) * M);
  add_block_at(position(b, b), b, std::abs(c) * M);
  ++lumped_;
}

Eigen::SparseMatrix<double> SparseHessian::full() const
{
  Eigen::SparseMatrix<double> upper = matrix_.triangularView<Eigen::Upper>();
  return upper.selfadjointView<Eigen::Upper>();
}

void SparseHessian::add_block(int i, int j, const Eigen::Matrix3d& block)
{
  if (i > j) return; // the lower block triangle is not stored
  const int k = position(i, j);
  if (k < 0) throw std::logic_error("SparseHessian: block outside the pattern");
  add_block_at(k, j, block);
}

} // namespace fibermold
