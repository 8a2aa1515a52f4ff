#include "sim/soft_dirichlet.hpp"

#include <algorithm>
#include <stdexcept>

namespace fibermold {

SoftDirichlet::SoftDirichlet(std::vector<ShapeEval> at_nodes, std::vector<Eigen::Vector3d> targets, double stiffness)
    : at_(std::move(at_nodes)), targets_(std::move(targets)), k_(stiffness)
{
}

void SoftDirichlet::move_targets(std::size_t first, const std::vector<Eigen::Vector3d>& targets)
{
  if (first + targets.size() > targets_.size())
    throw std::out_of_range("SoftDirichlet::move_targets: past the held points");
  std::copy(targets.begin(), targets.end(), targets_.begin() + static_cast<std::ptrdiff_t>(first));
}

double SoftDirichlet::value(const Eigen::VectorXd& x) const
{
  double e = 0;
  for (std::size_t p = 0; p < at_.size(); ++p) e += k_ / 2 * (at_[p].position(x) - targets_[p]).squaredNorm();
  return e;
}

void SoftDirichlet::add_gradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const
{
  // ∂E/∂x_j = k (x(X_i) − X̂_i) N_j(X_i)
  for (std::size_t p = 0; p < at_.size(); ++p) {
    const Eigen::Vector3d r = k_ * (at_[p].position(x) - targets_[p]);
    for (Eigen::Index k = 0; k < at_[p].size(); ++k) g.segment<3>(3 * at_[p].nodes[k]) += at_[p].N[k] * r;
  }
}

void SoftDirichlet::add_hessian(const Eigen::VectorXd&, SparseHessian& H, bool) const
{
  // ∂²E/∂x_i∂x_j = k N_i N_j I: positive semi-definite as it is.
  for (const ShapeEval& s : at_)
    for (Eigen::Index a = 0; a < s.size(); ++a)
      for (Eigen::Index b = 0; b < s.size(); ++b)
        H.add_block(s.nodes[a], s.nodes[b], k_ * s.N[a] * s.N[b] * Eigen::Matrix3d::Identity());
}

void SoftDirichlet::add_hessian_product(const Eigen::VectorXd&, const Eigen::VectorXd& v, Eigen::VectorXd& out) const
{
  // Σ_j k N_i N_j v_j = k N_i v(X_i): the gradient's formula with v for x and no target.
  for (const ShapeEval& s : at_) {
    const Eigen::Vector3d r = k_ * s.position(v);
    for (Eigen::Index k = 0; k < s.size(); ++k) out.segment<3>(3 * s.nodes[k]) += s.N[k] * r;
  }
}

void SoftDirichlet::stencils(std::vector<std::vector<int>>& out) const
{
  for (const ShapeEval& s : at_) out.push_back(s.nodes);
}

} // namespace fibermold
