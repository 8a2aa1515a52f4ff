#include "sim/muscle_energy.hpp"

#include <Eigen/Eigenvalues>

namespace fibermold {

MuscleEnergy::MuscleEnergy(const Basis& basis, const MuscleModel& model, FiberSegments segments, double pressure)
    : model_(model), segments_(std::move(segments)), pressure_(pressure)
{
  for (std::size_t j = 0; j < segments_.centres.size(); ++j) {
    at_.push_back(basis.at(segments_.centres[j], 1));
    alpha_.push_back(at_.back().dN * segments_.vectors[j]);
  }
}

MuscleEnergy::SegmentState MuscleEnergy::state(const Eigen::VectorXd& x, std::size_t j) const
{
  // F d = Σ_i x_i (∇N_i · d)
  Eigen::Vector3d Fd = Eigen::Vector3d::Zero();
  for (Eigen::Index k = 0; k < at_[j].size(); ++k) Fd += alpha_[j][k] * x.segment<3>(3 * at_[j].nodes[k]);
  SegmentState s;
  s.rest_length = (model_.rest_strain(pressure_) + 1) * segments_.vectors[j].norm();
  s.length = Fd.norm();
  s.strain = s.length / s.rest_length - 1;
  s.direction = Fd / s.length;
  return s;
}

std::vector<double> MuscleEnergy::strains(const Eigen::VectorXd& x) const
{
  std::vector<double> e;
  for (std::size_t j = 0; j < at_.size(); ++j) e.push_back(state(x, j).strain);
  return e;
}

double MuscleEnergy::value(const Eigen::VectorXd& x) const
{
  // eq. 10: Σ_j Ψ_act(p, ε_j) A_act L_j
  const double area = model_.parameters().area();
  double e = 0;
  for (std::size_t j = 0; j < at_.size(); ++j) {
    const SegmentState s = state(x, j);
    e += model_.density(pressure_, s.strain).psi * area * s.rest_length;
  }
  return e;
}

void MuscleEnergy::add_gradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const
{
  // ∂E/∂x_i = A_act L Ψ_ε ∂ε/∂x_i = A_act Ψ_ε n α_i
  const double area = model_.parameters().area();
  for (std::size_t j = 0; j < at_.size(); ++j) {
    const SegmentState s = state(x, j);
    const Eigen::Vector3d f = area * model_.density(pressure_, s.strain).d_eps * s.direction;
    for (Eigen::Index k = 0; k < at_[j].size(); ++k) g.segment<3>(3 * at_[j].nodes[k]) += alpha_[j][k] * f;
  }
}

void MuscleEnergy::add_hessian(const Eigen::VectorXd& x, SparseHessian& H, bool project) const
{
  // ∂²E/∂x_i∂x_k = α_i α_k M,  M = A_act [Ψ_εε / L n nᵀ + Ψ_ε / l (I − n nᵀ)]
  // α αᵀ is positive semi-definite, so projecting M (eigenvalues along n and across it) suffices.
  const double area = model_.parameters().area();
  for (std::size_t j = 0; j < at_.size(); ++j) {
    const SegmentState s = state(x, j);
    const MuscleDensity d = model_.density(pressure_, s.strain);
    double along = area * d.d_eps_eps / s.rest_length, across = area * d.d_eps / s.length;
    if (project) {
      along = std::max(along, 0.0);
      across = std::max(across, 0.0);
    }
    const Eigen::Matrix3d nn = s.direction * s.direction.transpose();
    const Eigen::Matrix3d M = along * nn + across * (Eigen::Matrix3d::Identity() - nn);
    const ShapeEval& e = at_[j];
    for (Eigen::Index a = 0; a < e.size(); ++a)
      for (Eigen::Index b = 0; b < e.size(); ++b) H.add_block(e.nodes[a], e.nodes[b], alpha_[j][a] * alpha_[j][b] * M);
  }
}

void MuscleEnergy::stencils(std::vector<std::vector<int>>& out) const
{
  for (const ShapeEval& e : at_) out.push_back(e.nodes);
}

} // namespace fibermold
