#include "sim/neo_hookean.hpp"
#include "sim/point_forces.hpp"
#include "sim/stiffness_column.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

namespace fibermold {

namespace {

// Ψ = μ/2 (tr(FᵀF) − 3) − μ ln J + λ/2 ln² J
double density(const Eigen::Matrix3d& F, double lnJ, const LameParameters& l)
{
  return l.mu / 2 * (F.squaredNorm() - 3) - l.mu * lnJ + l.lambda / 2 * lnJ * lnJ;
}

// P = μ (F − F⁻ᵀ) + λ ln J F⁻ᵀ
Eigen::Matrix3d stress(const Eigen::Matrix3d& F, const Eigen::Matrix3d& FinvT, double lnJ, const LameParameters& l)
{
  return l.mu * (F - FinvT) + l.lambda * lnJ * FinvT;
}

} // namespace

double neo_hookean_density(const Eigen::Matrix3d& F, const LameParameters& l)
{
  const double J = F.determinant();
  if (!(J > 0)) return HUGE_VAL;
  return density(F, std::log(J), l);
}

Eigen::Matrix3d neo_hookean_stress(const Eigen::Matrix3d& F, const LameParameters& l)
{
  return stress(F, F.inverse().transpose(), std::log(F.determinant()), l);
}

Eigen::Matrix<double, 9, 9> neo_hookean_stress_derivative(const Eigen::Matrix3d& F, const LameParameters& l)
{
  // ∂P_ij/∂F_kl = μ δ_ik δ_jl + λ F⁻ᵀ_ij F⁻ᵀ_kl + (μ − λ ln J) F⁻ᵀ_il F⁻ᵀ_kj
  const Eigen::Matrix3d G = F.inverse().transpose();
  const double c = l.mu - l.lambda * std::log(F.determinant());
  Eigen::Matrix<double, 9, 9> D;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k)
        for (int m = 0; m < 3; ++m)
          D(3 * i + j, 3 * k + m) =
              (i == k && j == m ? l.mu : 0) + l.lambda * G(i, j) * G(k, m) + c * G(i, m) * G(k, j);
  return D;
}

Eigen::Matrix<double, 9, 9> neo_hookean_stress_derivative_psd(const Eigen::Matrix3d& F, const LameParameters& l)
{
  // With F = U Σ Vᵀ, G = F⁻ᵀ = U D Vᵀ (D = Σ⁻¹) and δF = U δF̂ Vᵀ, the second variation is
  //   δF : ∂P/∂F : δF = μ |δF̂|² + λ (Σ d_i δF̂_ii)² + (μ − λ ln J) Σ_ik d_i d_k δF̂_ik δF̂_ki,
  // so its eigenvectors are U E Vᵀ for E = (e_i e_kᵀ ± e_k e_iᵀ)/√2 (eigenvalues μ ± c d_i d_k, i < k)
  // and E = diag(w) for the eigenvectors w of μ I + λ d dᵀ + c diag(d²): the analytic eigensystem
  // of Smith, de Goes and Kim (2019) for this energy. The projection adds back the negative part.
  Eigen::Matrix<double, 9, 9> C = neo_hookean_stress_derivative(F, l);
  // The SVD from FᵀF = V Σ² Vᵀ and U = F V Σ⁻¹ (F is invertible).
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> right(F.transpose() * F);
  const Eigen::Matrix3d& V = right.eigenvectors();
  const Eigen::Vector3d d = right.eigenvalues().cwiseSqrt().cwiseInverse();
  const Eigen::Matrix3d U = F * V * d.asDiagonal();
  const double c = l.mu - l.lambda * std::log(F.determinant());
  const auto subtract = [&](double eigenvalue, const Eigen::Matrix3d& mode) {
    const Eigen::Matrix<double, 3, 3, Eigen::RowMajor> row_major = mode;
    const Eigen::Map<const Eigen::Matrix<double, 9, 1>> e(row_major.data());
    C.noalias() -= eigenvalue * e * e.transpose();
  };
  for (int i = 0; i < 3; ++i)
    for (int k = i + 1; k < 3; ++k)
      for (const double sign : {1.0, -1.0}) {
        const double eigenvalue = l.mu + sign * c * d[i] * d[k];
        if (eigenvalue < 0)
          subtract(eigenvalue,
                   (U.col(i) * V.col(k).transpose() + sign * U.col(k) * V.col(i).transpose()) / std::sqrt(2.0));
      }
  const Eigen::Matrix3d scaling = l.mu * Eigen::Matrix3d::Identity() + l.lambda * d * d.transpose() +
                                  c * d.cwiseAbs2().asDiagonal().toDenseMatrix();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(scaling);
  for (int m = 0; m < 3; ++m)
    if (eig.eigenvalues()[m] < 0)
      subtract(eig.eigenvalues()[m], U * eig.eigenvectors().col(m).asDiagonal() * V.transpose());
  return C;
}

NeoHookean::NeoHookean(const QuadraturePoints& qp, Eigen::Index num_nodes, LameParameters lame)
    : qp_(qp), incidence_(node_incidence(qp, num_nodes)), lame_(lame)
{
}

Eigen::Matrix3d NeoHookean::deformation_gradient(const Eigen::VectorXd& x, Eigen::Index q) const
{
  const int k = qp_.offset[q];
  return gather_deformation_gradient(x.data(), &qp_.node[k], &qp_.dN[k], qp_.offset[q + 1] - k);
}

double NeoHookean::value(const Eigen::VectorXd& x) const
{
  return tbb::parallel_deterministic_reduce(
      tbb::blocked_range<Eigen::Index>(0, qp_.size(), chunk_size()), 0.0,
      [&](const tbb::blocked_range<Eigen::Index>& range, double sum) {
        for (Eigen::Index q = range.begin(); q < range.end(); ++q)
          sum += qp_.volume[q] * neo_hookean_density(deformation_gradient(x, q), lame_);
        return sum;
      },
      std::plus<>());
}

bool NeoHookean::is_step_valid(const Eigen::VectorXd& x) const
{
  return tbb::parallel_reduce(
      tbb::blocked_range<Eigen::Index>(0, qp_.size()), true,
      [&](const tbb::blocked_range<Eigen::Index>& range, bool ok) {
        for (Eigen::Index q = range.begin(); ok && q < range.end(); ++q)
          ok = deformation_gradient(x, q).determinant() > 0;
        return ok;
      },
      std::logical_and<>());
}

void NeoHookean::add_gradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const { value_and_gradient(x, g); }

double NeoHookean::value_and_gradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const
{
  // One pass over the points: F once for the validity, Ψ and P; each point's forces
  //   ∂E/∂x_i += V_q P_q ∇N_i(X_q)
  // go into the gradient of its chunk of points (the points stream through memory in order; a
  // per-node gather would revisit each point once per node). Fixed chunks summed in a fixed tree:
  // the same bits whatever the number of threads, so that runs reproduce.
  struct Partial {
    double E = 0;
    Eigen::VectorXd g;
  };
  const Partial total = tbb::parallel_deterministic_reduce(
      tbb::blocked_range<Eigen::Index>(0, qp_.size(), chunk_size()), Partial{},
      [&](const tbb::blocked_range<Eigen::Index>& range, Partial p) {
        if (p.g.size() == 0) p.g = Eigen::VectorXd::Zero(g.size());
        for (Eigen::Index q = range.begin(); q < range.end() && p.E < HUGE_VAL; ++q) {
          const Eigen::Matrix3d F = deformation_gradient(x, q);
          const double J = F.determinant();
          if (!(J > 0)) {
            p.E = HUGE_VAL;
            break;
          }
          const double lnJ = std::log(J);
          p.E += qp_.volume[q] * density(F, lnJ, lame_);
          const int k = qp_.offset[q];
          scatter_point_forces(qp_.volume[q] * stress(F, F.inverse().transpose(), lnJ, lame_), &qp_.node[k], &qp_.dN[k],
                               qp_.offset[q + 1] - k, p.g.data());
        }
        return p;
      },
      [](Partial a, const Partial& b) {
        a.E += b.E;
        if (a.g.size() == 0)
          a.g = b.g;
        else if (b.g.size() != 0)
          a.g += b.g;
        return a;
      });
  if (!(total.E < HUGE_VAL)) return HUGE_VAL;
  g += total.g;
  return total.E;
}

void NeoHookean::add_hessian_product(const Eigen::VectorXd& x, const Eigen::VectorXd& v, Eigen::VectorXd& out) const
{
  hessian_at(x)->add(v, out);
}

std::unique_ptr<HessianProduct> NeoHookean::hessian_at(const Eigen::VectorXd& x) const
{
  // The gradient's pass with P's derivative along v: at each point δF = Σ_k v_{i_k} ∇N_kᵀ and
  //   δP = μ δF + λ (G : δF) G + (μ − λ ln J) G δFᵀ G,  G = F⁻ᵀ
  // (δG = −G δFᵀ G, δ ln J = G : δF), scattered as V_q δP ∇N_i. G and μ − λ ln J depend on x
  // alone and are kept per point, so a product is one gather and one scatter, against the two
  // gradients of a central difference (and none of its round-off). The same fixed chunks and tree
  // as the gradient: the same bits on any number of threads.
  struct Point {
    Eigen::Matrix3d G;
    double c;
  };
  class AtState final : public HessianProduct {
  public:
    AtState(const NeoHookean& e, std::vector<Point> points) : e_(e), points_(std::move(points)) {}
    void add(const Eigen::VectorXd& v, Eigen::VectorXd& out) const override
    {
      const QuadraturePoints& qp = e_.qp_;
      const LameParameters& lame = e_.lame_;
      const Eigen::VectorXd total = tbb::parallel_deterministic_reduce(
          tbb::blocked_range<Eigen::Index>(0, qp.size(), e_.chunk_size()), Eigen::VectorXd(),
          [&](const tbb::blocked_range<Eigen::Index>& range, Eigen::VectorXd p) {
            if (p.size() == 0) p = Eigen::VectorXd::Zero(out.size());
            for (Eigen::Index q = range.begin(); q < range.end(); ++q) {
              const int k = qp.offset[q], count = qp.offset[q + 1] - k;
              const Eigen::Matrix3d dF = gather_deformation_gradient(v.data(), &qp.node[k], &qp.dN[k], count);
              const Eigen::Matrix3d& G = points_[q].G;
              const Eigen::Matrix3d dP =
                  lame.mu * dF + lame.lambda * G.cwiseProduct(dF).sum() * G + points_[q].c * G * dF.transpose() * G;
              scatter_point_forces(qp.volume[q] * dP, &qp.node[k], &qp.dN[k], count, p.data());
            }
            return p;
          },
          [](Eigen::VectorXd a, const Eigen::VectorXd& b) {
            if (a.size() == 0) return b;
            if (b.size() != 0) a += b;
            return a;
          });
      if (total.size() != 0) out += total;
    }

  private:
    const NeoHookean& e_;
    std::vector<Point> points_;
  };
  std::vector<Point> points(static_cast<std::size_t>(qp_.size()));
  tbb::parallel_for(Eigen::Index{0}, qp_.size(), [&](Eigen::Index q) {
    const Eigen::Matrix3d F = deformation_gradient(x, q);
    points[q] = {F.inverse().transpose(), lame_.mu - lame_.lambda * std::log(F.determinant())};
  });
  return std::make_unique<AtState>(*this, std::move(points));
}

Eigen::Index NeoHookean::chunk_size() const { return std::max<Eigen::Index>(1024, qp_.size() / 16); }

void NeoHookean::add_hessian(const Eigen::VectorXd& x, SparseHessian& H, bool project) const
{
  // The exact stress derivative goes to the assembly as the 12 numbers it is made of, the
  // projected one as its 81 entries.
  std::vector<NeoHookeanPoint> exact(project ? 0 : static_cast<std::size_t>(qp_.size()));
  std::vector<StiffnessLayout> W(project ? static_cast<std::size_t>(qp_.size()) : 0);
  tbb::parallel_for(Eigen::Index{0}, qp_.size(), [&](Eigen::Index q) {
    const Eigen::Matrix3d F = deformation_gradient(x, q);
    const double V = qp_.volume[q];
    if (project)
      W[q] = stiffness_layout(V * neo_hookean_stress_derivative_psd(F, lame_));
    else
      exact[q] = {F.inverse().transpose(), V * lame_.mu, V * lame_.lambda,
                  V * (lame_.mu - lame_.lambda * std::log(F.determinant()))};
  });
  // Column j of the Hessian gathers every point q touching j, for q's nodes i ≤ j: into a padded
  // copy (4 entries per block column) when the AVX2 kernels run, added to the matrix at the end.
  struct Scratch {
    std::vector<int> position;
    std::vector<double> values;
  };
  const bool padded = stiffness_simd_available();
  tbb::enumerable_thread_specific<Scratch> scratch(
      Scratch{std::vector<int>(static_cast<std::size_t>(H.num_nodes()), -1), {}});
  const auto n = static_cast<Eigen::Index>(incidence_.offset.size()) - 1;
  tbb::parallel_for(Eigen::Index{0}, n, [&](Eigen::Index j) {
    Scratch& local = scratch.local();
    std::vector<int>& pos = local.position;
    const auto& nb = H.neighbours(j);
    const auto L = static_cast<std::ptrdiff_t>(nb.size());
    const int lanes = padded ? 4 : 3;
    for (std::size_t k = 0; k < nb.size(); ++k) pos[nb[k]] = lanes * static_cast<int>(k);
    if (padded) local.values.assign(static_cast<std::size_t>(12 * L), 0.0);
    const StiffnessColumn column{padded ? local.values.data() : H.column_values(j), lanes * L, pos.data(), padded};
    for (int e = incidence_.offset[j]; e < incidence_.offset[j + 1]; ++e) {
      const auto [q, kj] = incidence_.entry[e];
      if (e + 2 < incidence_.offset[j + 1]) {
        const auto [q2, k2] = incidence_.entry[e + 2];
        const char* next =
            project ? reinterpret_cast<const char*>(W[q2].data()) : reinterpret_cast<const char*>(&exact[q2]);
        const int lines = project ? 11 : 2;
        for (int line = 0; line < lines; ++line) __builtin_prefetch(next + 64 * line);
        const char* gradients = reinterpret_cast<const char*>(qp_.dN[qp_.offset[q2]].data());
        const auto bytes = static_cast<std::size_t>(k2 + 1 - qp_.offset[q2]) * sizeof(Eigen::Vector3d);
        for (std::size_t at = 0; at < bytes; at += 64) __builtin_prefetch(gradients + at);
        __builtin_prefetch(&qp_.node[qp_.offset[q2]]);
      }
      // A point's nodes ascend, so those ≤ j are its entries up to j's.
      const int first = qp_.offset[q];
      if (project)
        add_point_to_column(W[q].data(), qp_.dN[kj], &qp_.dN[first], &qp_.node[first], kj + 1 - first, column);
      else
        add_neo_hookean_point_to_column(exact[q], qp_.dN[kj], &qp_.dN[first], &qp_.node[first], kj + 1 - first, column);
    }
    if (padded) {
      double* values = H.column_values(j);
      for (std::ptrdiff_t b = 0; b < 3; ++b)
        for (std::ptrdiff_t k = 0; k < L; ++k)
          for (int a = 0; a < 3; ++a) values[3 * L * b + 3 * k + a] += local.values[4 * L * b + 4 * k + a];
    }
    for (int i : nb) pos[i] = -1;
  });
}

void NeoHookean::stencils(std::vector<std::vector<int>>& out) const
{
  for (Eigen::Index q = 0; q < qp_.size(); ++q)
    out.emplace_back(qp_.node.begin() + qp_.offset[q], qp_.node.begin() + qp_.offset[q + 1]);
}

} // namespace fibermold
