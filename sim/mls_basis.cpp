#include "sim/mls_basis.hpp"

#include <array>
#include <stdexcept>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <fmt/format.h>
#include <nanoflann.hpp>

#include "core/units.hpp"
#include "sim/mls_weight.hpp"

namespace fibermold {

struct MlsBasis::Tree {
  using Index = nanoflann::KDTreeEigenMatrixAdaptor<Eigen::MatrixX3d>;
  explicit Tree(const Eigen::MatrixX3d& points) : index(3, std::cref(points), 16) {}
  Index index;
};

namespace {

/// The polynomial basis p(y) in scaled coordinates y = (X − c) / r, with its derivatives at y = 0.
struct PolynomialBasis {
  int size;
  Eigen::VectorXd value(const Eigen::Vector3d& y) const
  {
    Eigen::VectorXd p(size);
    p.head<4>() << 1, y.x(), y.y(), y.z();
    if (size == 10)
      p.tail<6>() << y.x() * y.x(), y.y() * y.y(), y.z() * y.z(), y.x() * y.y(), y.y() * y.z(), y.x() * y.z();
    return p;
  }
  /// ∂p/∂y_k at y = 0.
  Eigen::VectorXd d(int k) const
  {
    Eigen::VectorXd p = Eigen::VectorXd::Zero(size);
    p[1 + k] = 1;
    return p;
  }
  /// ∂²p/∂y_k∂y_l at y = 0.
  Eigen::VectorXd dd(int k, int l) const
  {
    Eigen::VectorXd p = Eigen::VectorXd::Zero(size);
    if (size == 10) {
      if (k == l)
        p[4 + k] = 2;
      else {
        const int lo = std::min(k, l), hi = std::max(k, l);
        p[lo == 0 && hi == 1 ? 7 : lo == 1 && hi == 2 ? 8 : 9] = 1;
      }
    }
    return p;
  }
};

double condition_number(const Eigen::MatrixXd& G)
{
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(G, Eigen::EigenvaluesOnly);
  const double lo = eig.eigenvalues().minCoeff(), hi = eig.eigenvalues().maxCoeff();
  return lo > 0 ? hi / lo : HUGE_VAL;
}

} // namespace

MlsBasis::MlsBasis(Eigen::MatrixX3d nodes, MlsOptions options)
    : nodes_(std::move(nodes)), options_(options), tree_(std::make_unique<Tree>(nodes_))
{
  if (!(options_.radius > 0)) throw std::invalid_argument("MLS radius must be > 0");
}

MlsBasis::~MlsBasis() = default;

MlsConditioning MlsBasis::conditioning() const
{
  std::lock_guard lock(mutex_);
  return conditioning_;
}

ShapeEval MlsBasis::at(const Eigen::Vector3d& X, int order, Eigen::Index) const
{
  const PolynomialBasis basis{options_.quadratic ? 10 : 4};
  const int m = basis.size;
  double r = options_.radius;
  std::vector<std::pair<Eigen::Index, double>> found;
  Eigen::MatrixXd G, B; // B: column j = b_j
  std::vector<MlsWeight> weights;
  for (int attempt = 0;; ++attempt) {
    found.clear();
    tree_->index.index->radiusSearch(X.data(), r * r, found, nanoflann::SearchParams(32, 0, false));
    B.resize(m, static_cast<Eigen::Index>(found.size()));
    G = Eigen::MatrixXd::Zero(m, m);
    weights.clear();
    for (std::size_t j = 0; j < found.size(); ++j) {
      const Eigen::Vector3d delta = X - nodes_.row(found[j].first).transpose();
      weights.push_back(mls_weight(delta, r));
      B.col(static_cast<Eigen::Index>(j)) = basis.value(-delta / r);
      G += weights.back().w * B.col(static_cast<Eigen::Index>(j)) * B.col(static_cast<Eigen::Index>(j)).transpose();
    }
    if (static_cast<int>(found.size()) >= m && condition_number(G) <= options_.max_condition) break;
    if (attempt == options_.max_widenings)
      throw std::runtime_error(fmt::format(
          "MLS shape functions are singular at ({:.2f}, {:.2f}, {:.2f}) mm: {} nodes within {:.3g} mm are too few or "
          "co-planar for a {} basis; raise [sim] mls_radius or refine the mesh there",
          X.x() / units::mm, X.y() / units::mm, X.z() / units::mm, found.size(), r / units::mm, name()));
    r *= 1.5;
    std::lock_guard lock(mutex_);
    if (attempt == 0 && conditioning_.widened++ == 0) conditioning_.example = X;
    conditioning_.largest_radius = std::max(conditioning_.largest_radius, r);
  }

  const Eigen::LLT<Eigen::MatrixXd> llt(G);
  // Derivatives of b(X) = p((X − c)/r) at c = X: N_i does not depend on c, so c is held fixed.
  const Eigen::VectorXd b = basis.value(Eigen::Vector3d::Zero());
  const Eigen::VectorXd a = llt.solve(b); // a = G⁻¹ b(X)
  const Eigen::Index n = B.cols();
  ShapeEval out;
  out.nodes.reserve(found.size());
  for (const auto& f : found) out.nodes.push_back(static_cast<int>(f.first));
  out.N.resize(n);
  out.dN.setZero(n, 3);
  const Eigen::VectorXd Ba = B.transpose() * a; // b_iᵀ a
  for (Eigen::Index i = 0; i < n; ++i) out.N[i] = weights[i].w * Ba[i];
  if (order < 1) return out;

  // ∂_k G = Σ_i ∂_k w_i b_i b_iᵀ;  ∂_k a = G⁻¹ (∂_k b − ∂_k G a)
  std::array<Eigen::MatrixXd, 3> dG;
  std::array<Eigen::VectorXd, 3> da, Bda;
  for (int k = 0; k < 3; ++k) {
    Eigen::VectorXd wk(n);
    for (Eigen::Index i = 0; i < n; ++i) wk[i] = weights[i].grad[k];
    dG[k] = B * wk.asDiagonal() * B.transpose();
    da[k] = llt.solve(basis.d(k) / r - dG[k] * a);
    Bda[k] = B.transpose() * da[k];
  }
  // ∇N_i = ∇w_i (b_iᵀ a) + w_i b_iᵀ ∇a
  for (Eigen::Index i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) out.dN(i, k) = weights[i].grad[k] * Ba[i] + weights[i].w * Bda[k][i];
  if (order < 2) return out;

  // ∂_kl a = G⁻¹ (∂_kl b − ∂_kl G a − ∂_k G ∂_l a − ∂_l G ∂_k a)
  out.ddN.assign(static_cast<std::size_t>(n), Eigen::Matrix3d::Zero());
  for (int k = 0; k < 3; ++k)
    for (int l = k; l < 3; ++l) {
      Eigen::VectorXd wkl(n);
      for (Eigen::Index i = 0; i < n; ++i) wkl[i] = weights[i].hess(k, l);
      const Eigen::MatrixXd ddG = B * wkl.asDiagonal() * B.transpose();
      const Eigen::VectorXd dda = llt.solve(basis.dd(k, l) / (r * r) - ddG * a - dG[k] * da[l] - dG[l] * da[k]);
      const Eigen::VectorXd Bdda = B.transpose() * dda;
      for (Eigen::Index i = 0; i < n; ++i) {
        const MlsWeight& w = weights[i];
        const double v = w.hess(k, l) * Ba[i] + w.grad[k] * Bda[l][i] + w.grad[l] * Bda[k][i] + w.w * Bdda[i];
        out.ddN[i](k, l) = v;
        out.ddN[i](l, k) = v;
      }
    }
  return out;
}

} // namespace fibermold
