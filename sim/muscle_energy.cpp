#include "sim/muscle_energy.hpp"

namespace fibermold {

MuscleEnergy::MuscleEnergy(const Basis& basis, const MuscleModel& model, HermiteSpline spline, std::vector<double> t,
                           double pressure)
    : model_(model), spline_(std::move(spline)), segments_(segments_at(spline_, std::move(t))), pressure_(pressure)
{
  for (std::size_t j = 0; j < segments_.centres.size(); ++j) {
    at_.push_back(basis.at(segments_.centres[j], 2));
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

FiberParameterGradient MuscleEnergy::zero_gradient() const
{
  FiberParameterGradient g;
  g.points.assign(spline_.points().size(), Eigen::Vector3d::Zero());
  g.tangents.assign(spline_.points().size(), Eigen::Vector3d::Zero());
  return g;
}

void MuscleEnergy::chain_to_parameters(std::size_t j, const Eigen::Vector3d& by_d, const Eigen::Vector3d& by_c,
                                       FiberParameterGradient& out) const
{
  // d_j = e_{j+1} − e_j, c_j = (e_j + e_{j+1})/2, and each endpoint e = h00 P_k + h10 T_k + h01 P_{k+1} + h11 T_{k+1}.
  for (int end = 0; end < 2; ++end) {
    const Eigen::Vector3d by_e = (end == 0 ? -by_d : by_d) + by_c / 2;
    int k;
    double w[4];
    spline_.weights(segments_.t[j + end], k, w);
    out.points[k] += w[0] * by_e;
    out.tangents[k] += w[1] * by_e;
    out.points[k + 1] += w[2] * by_e;
    out.tangents[k + 1] += w[3] * by_e;
  }
}

Eigen::Matrix3d MuscleEnergy::centre_derivative(const Eigen::VectorXd& v, std::size_t j) const
{
  // ∂/∂c of (Σ_i v_i ∇N_i(c)ᵀ) d_j = Σ_i v_i (∇∇N_i d_j)ᵀ
  Eigen::Matrix3d D = Eigen::Matrix3d::Zero();
  for (Eigen::Index i = 0; i < at_[j].size(); ++i)
    D += v.segment<3>(3 * at_[j].nodes[i]) * (at_[j].ddN[i] * segments_.vectors[j]).transpose();
  return D;
}

FiberParameterGradient MuscleEnergy::parameter_gradient(const Eigen::VectorXd& x) const
{
  // E_j = A Ψ(p, ε) L with ε = l/L − 1:  ∂E_j/∂l = A Ψ_ε,  ∂E_j/∂L = A (Ψ − Ψ_ε (1 + ε)).
  // l = |F(c) d|: ∂l/∂d = Fᵀn, ∂l/∂c = Σ_i (n·x_i) ∇∇N_i d.  L = (1 + ε_L)|d|: ∂L/∂d = (1 + ε_L) d/|d|, ∂L/∂p = ε_L' |d|.
  const double area = model_.parameters().area();
  const double rest = 1 + model_.rest_strain(pressure_), rest_p = model_.parameters().rest_strain_slope;
  FiberParameterGradient g = zero_gradient();
  for (std::size_t j = 0; j < at_.size(); ++j) {
    const SegmentState s = state(x, j);
    const MuscleDensity m = model_.density(pressure_, s.strain);
    const ShapeEval& e = at_[j];
    const Eigen::Vector3d& d = segments_.vectors[j];
    const Eigen::Matrix3d F = e.deformation_gradient(x);
    const Eigen::Vector3d dl_dc = centre_derivative(x, j).transpose() * s.direction;
    const double by_l = area * m.d_eps, by_L = area * (m.psi - m.d_eps * (1 + s.strain));
    chain_to_parameters(j, by_l * F.transpose() * s.direction + by_L * rest * d.normalized(), by_l * dl_dc, g);
    // ∂E_j/∂p = A L Ψ_p + ∂E_j/∂L ε_L' |d|
    g.pressure += area * s.rest_length * m.d_p + by_L * rest_p * d.norm();
  }
  return g;
}

FiberParameterGradient MuscleEnergy::mixed_derivative(const Eigen::VectorXd& x, const Eigen::VectorXd& lambda) const
{
  // φ = λ · ∂E/∂x = Σ_j A Ψ_ε(p, ε_j) q_j,  q = n · w,  u = F d,  w = G d,  G = Σ_i λ_i ∇N_iᵀ, l = |u|.
  //   ∂q = (w − q n)·∂u / l + n·∂w,   ∂ε/∂d = (Fᵀn − (1 + ε)(1 + ε_L) d/|d|) / L,   ∂ε/∂c = Duᵀ n / L,
  //   ∂u/∂c = Du = Σ_i x_i (∇∇N_i d)ᵀ,  ∂w/∂c = Dw = Σ_i λ_i (∇∇N_i d)ᵀ,  ∂ε/∂p = −(1 + ε) ε_L' / (1 + ε_L).
  //   ∂φ_j = A [Ψ_εε q ∂ε + Ψ_ε ∂q] (+ A Ψ_εp q for p).
  const double area = model_.parameters().area();
  const double rest = 1 + model_.rest_strain(pressure_), rest_p = model_.parameters().rest_strain_slope;
  FiberParameterGradient g = zero_gradient();
  for (std::size_t j = 0; j < at_.size(); ++j) {
    const SegmentState s = state(x, j);
    const MuscleDensity m = model_.density(pressure_, s.strain);
    const ShapeEval& e = at_[j];
    const Eigen::Vector3d& d = segments_.vectors[j];
    const Eigen::Matrix3d F = e.deformation_gradient(x), G = e.deformation_gradient(lambda);
    const Eigen::Matrix3d Du = centre_derivative(x, j), Dw = centre_derivative(lambda, j);
    const Eigen::Vector3d& n = s.direction;
    const Eigen::Vector3d w = G * d;
    const double q = n.dot(w), l = s.length, L = s.rest_length;
    const Eigen::Vector3d de_dd = (F.transpose() * n - (1 + s.strain) * rest * d.normalized()) / L;
    const Eigen::Vector3d de_dc = Du.transpose() * n / L;
    const Eigen::Vector3d dq_dd = F.transpose() * (w - q * n) / l + G.transpose() * n;
    const Eigen::Vector3d dq_dc = Du.transpose() * (w - q * n) / l + Dw.transpose() * n;
    chain_to_parameters(j, area * (m.d_eps_eps * q * de_dd + m.d_eps * dq_dd),
                        area * (m.d_eps_eps * q * de_dc + m.d_eps * dq_dc), g);
    const double de_dp = -(1 + s.strain) * rest_p / rest;
    g.pressure += area * (m.d_eps_p + m.d_eps_eps * de_dp) * q;
  }
  return g;
}

} // namespace fibermold
