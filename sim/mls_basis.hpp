#pragma once
// Moving-least-squares shape functions (paper eq. 6–7): N_i(X) = w_i(X) b_iᵀ G(X)⁻¹ b(X), with
// G = Σ_i w_i b_i b_iᵀ, a linear [1, X, Y, Z] or quadratic (10 monomials) basis b, and the C³ weight
// of support r. N, ∇N and ∇∇N exactly: ∂G⁻¹ = −G⁻¹ ∂G G⁻¹ and its second derivative.

#include <atomic>
#include <memory>
#include <mutex>

#include "sim/shape_functions.hpp"

namespace fibermold {

struct MlsOptions {
  bool quadratic = false;
  double radius = 0;          ///< r, m
  double max_condition = 1e8; ///< of G in scaled coordinates; beyond it r is widened
  int max_widenings = 4;      ///< × 1.5 each, before giving up
};

/// Where G was ill-conditioned: how often r had to be widened, and one place.
struct MlsConditioning {
  std::size_t widened = 0;
  Eigen::Vector3d example = Eigen::Vector3d::Zero();
  double largest_radius = 0;
};

class MlsBasis final : public Basis {
public:
  /// `nodes`: the n × 3 rest positions X_i (m).
  MlsBasis(Eigen::MatrixX3d nodes, MlsOptions options);
  ~MlsBasis() override;

  std::string name() const override { return options_.quadratic ? "mls-quadratic" : "mls-linear"; }
  /// Throws std::runtime_error naming the place (mm) when G stays singular after widening r.
  ShapeEval at(const Eigen::Vector3d& X, int order, Eigen::Index tet = -1) const override;

  MlsConditioning conditioning() const;
  double radius() const { return options_.radius; }

private:
  struct Tree;
  Eigen::MatrixX3d nodes_;
  MlsOptions options_;
  std::unique_ptr<Tree> tree_;
  mutable std::mutex mutex_;
  mutable MlsConditioning conditioning_;
};

} // namespace fibermold
