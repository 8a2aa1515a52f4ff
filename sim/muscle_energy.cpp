#include "sim/muscle_energy.hpp"

#include <map>

namespace fibermold {

MuscleEnergy::MuscleEnergy(const Basis& basis, const MuscleModel& model, HermiteSpline spline, std::vector<double> t,
                           double pressure)
    : model_(model), spline_(std::move(spline)), segments_(segments_at(spline_, std::move(t))), pressure_(pressure)
{
  for (double t_end : segments_.t) ends_.push_back(basis.at(spline_.position(t_end), 1));
  for (std::size_t j = 0; j + 1 < ends_.size(); ++j) {
    std::map<int, double> alpha; // node → N_i(e_{j+1}) − N_i(e_j)
    for (Eigen::Index k = 0; k < ends_[j].size(); ++k) alpha[ends_[j].nodes[k]] -= ends_[j].N[k];
    for (Eigen::Index k = 0; k < ends_[j + 1].size(); ++k) alpha[ends_[j + 1].nodes[k]] += ends_[j + 1].N[k];
    Chord c;
    c.alpha.resize(static_cast<Eigen::Index>(alpha.size()));
    for (const auto& [node, a] : alpha) {
      c.alpha[static_cast<Eigen::Index>(c.nodes.size())] = a;
      c.nodes.push_back(node);
    }
    chords_.push_back(std::move(c));
  }
}

MuscleEnergy::SegmentState MuscleEnergy::state(const Eigen::VectorXd& x, std::size_t j) const
{
  // u = x(e_{j+1}) − x(e_j) = Σ_i α_i x_i
  const Chord& c = chords_[j];
  Eigen::Vector3d u = Eigen::Vector3d::Zero();
  for (std::size_t k = 0; k < c.nodes.size(); ++k)
    u += c.alpha[static_cast<Eigen::Index>(k)] * x.segment<3>(3 * c.nodes[k]);
  SegmentState s;
  s.rest_length = (model_.rest_strain(pressure_) + 1) * segments_.vectors[j].norm();
  s.length = u.norm();
  s.strain = s.length / s.rest_length - 1;
  s.direction = u / s.length;
  return s;
}

std::vector<double> MuscleEnergy::strains(const Eigen::VectorXd& x) const
{
  std::vector<double> e;
  for (std::size_t j = 0; j < chords_.size(); ++j) e.push_back(state(x, j).strain);
  return e;
}

double MuscleEnergy::value(const Eigen::VectorXd& x) const
{
  // eq. 10: Σ_j Ψ_act(p, ε_j) A_act L_j
  const double area = model_.parameters().area();
  double e = 0;
  for (std::size_t j = 0; j < chords_.size(); ++j) {
    const SegmentState s = state(x, j);
    e += model_.density(pressure_, s.strain).psi * area * s.rest_length;
  }
  return e;
}

void MuscleEnergy::add_gradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const
{
  // ∂E/∂x_i = A_act L Ψ_ε ∂ε/∂x_i = A_act Ψ_ε n α_i
  const double area = model_.parameters().area();
  for (std::size_t j = 0; j < chords_.size(); ++j) {
    const SegmentState s = state(x, j);
    const Eigen::Vector3d f = area * model_.density(pressure_, s.strain).d_eps * s.direction;
    const Chord& c = chords_[j];
    for (std::size_t k = 0; k < c.nodes.size(); ++k)
      g.segment<3>(3 * c.nodes[k]) += c.alpha[static_cast<Eigen::Index>(k)] * f;
  }
}

Eigen::Matrix3d MuscleEnergy::chord_hessian(const Eigen::VectorXd& x, std::size_t j, bool project) const
{
  // M = A_act [Ψ_εε / L n nᵀ + Ψ_ε / l (I − n nᵀ)]: along the chord and across it.
  const double area = model_.parameters().area();
  const SegmentState s = state(x, j);
  const MuscleDensity d = model_.density(pressure_, s.strain);
  double along = area * d.d_eps_eps / s.rest_length, across = area * d.d_eps / s.length;
  if (project) {
    along = std::max(along, 0.0);
    across = std::max(across, 0.0);
  }
  const Eigen::Matrix3d nn = s.direction * s.direction.transpose();
  return along * nn + across * (Eigen::Matrix3d::Identity() - nn);
}

void MuscleEnergy::add_hessian(const Eigen::VectorXd& x, SparseHessian& H, bool project) const
{
  // ∂²E/∂x_i∂x_k = α_i α_k M (chord_hessian). α αᵀ is positive semi-definite, so projecting M
  // (eigenvalues along n and across it) suffices.
  // A pair of nodes the Hessian's pattern lacks (the pattern may be kept while the fiber moves:
  // newton_solver.hpp) is lumped onto their diagonals, which keeps the projected Hessian
  // positive semi-definite.
  for (std::size_t j = 0; j < chords_.size(); ++j) {
    const Eigen::Matrix3d M = chord_hessian(x, j, project);
    const Chord& c = chords_[j]; // nodes ascending
    for (std::size_t a = 0; a < c.nodes.size(); ++a) {
      const double alpha_a = c.alpha[static_cast<Eigen::Index>(a)];
      H.add_block(c.nodes[a], c.nodes[a], alpha_a * alpha_a * M);
      for (std::size_t b = a + 1; b < c.nodes.size(); ++b)
        H.add_coupling(c.nodes[a], c.nodes[b], alpha_a * c.alpha[static_cast<Eigen::Index>(b)], M);
    }
  }
}

void MuscleEnergy::add_hessian_product(const Eigen::VectorXd& x, const Eigen::VectorXd& v, Eigen::VectorXd& out) const
{
  hessian_at(x)->add(v, out);
}

std::unique_ptr<HessianProduct> MuscleEnergy::hessian_at(const Eigen::VectorXd& x) const
{
  // The exact (unprojected, unlumped) Hessian's product, chord by chord: with the chord of v,
  // δu = Σ_k α_k v_k, it adds α_i M δu at each of the chord's nodes. M depends on x alone and is
  // kept per chord. Until session 36 a central difference of the gradient (1e-6 relative).
  class AtState final : public HessianProduct {
  public:
    AtState(const MuscleEnergy& e, std::vector<Eigen::Matrix3d> M) : e_(e), M_(std::move(M)) {}
    void add(const Eigen::VectorXd& v, Eigen::VectorXd& out) const override
    {
      for (std::size_t j = 0; j < e_.chords_.size(); ++j) {
        const Chord& c = e_.chords_[j];
        Eigen::Vector3d du = Eigen::Vector3d::Zero();
        for (std::size_t k = 0; k < c.nodes.size(); ++k)
          du += c.alpha[static_cast<Eigen::Index>(k)] * v.segment<3>(3 * c.nodes[k]);
        const Eigen::Vector3d f = M_[j] * du;
        for (std::size_t k = 0; k < c.nodes.size(); ++k)
          out.segment<3>(3 * c.nodes[k]) += c.alpha[static_cast<Eigen::Index>(k)] * f;
      }
    }

  private:
    const MuscleEnergy& e_;
    std::vector<Eigen::Matrix3d> M_;
  };
  std::vector<Eigen::Matrix3d> M;
  M.reserve(chords_.size());
  for (std::size_t j = 0; j < chords_.size(); ++j) M.push_back(chord_hessian(x, j, false));
  return std::make_unique<AtState>(*this, std::move(M));
}

void MuscleEnergy::stencils(std::vector<std::vector<int>>& out) const
{
  for (const Chord& c : chords_) out.push_back(c.nodes);
}

FiberParameterGradient MuscleEnergy::zero_gradient() const
{
  FiberParameterGradient g;
  g.points.assign(spline_.points().size(), Eigen::Vector3d::Zero());
  g.tangents.assign(spline_.points().size(), Eigen::Vector3d::Zero());
  return g;
}

void MuscleEnergy::chain_to_parameters(std::size_t j, const Eigen::Vector3d& by_start, const Eigen::Vector3d& by_end,
                                       FiberParameterGradient& out) const
{
  // Each end e = h00 P_k + h10 T_k + h01 P_{k+1} + h11 T_{k+1}.
  for (int end = 0; end < 2; ++end) {
    const Eigen::Vector3d& by_e = end == 0 ? by_start : by_end;
    int k;
    double w[4];
    spline_.weights(segments_.t[j + end], k, w);
    out.points[k] += w[0] * by_e;
    out.tangents[k] += w[1] * by_e;
    out.points[k + 1] += w[2] * by_e;
    out.tangents[k + 1] += w[3] * by_e;
  }
}

FiberParameterGradient MuscleEnergy::parameter_gradient(const Eigen::VectorXd& x) const
{
  // E_j = A Ψ(p, ε) L with ε = l/L − 1:  ∂E_j/∂l = A Ψ_ε,  ∂E_j/∂L = A (Ψ − Ψ_ε (1 + ε)).
  // l = |x(e_{j+1}) − x(e_j)|: ∂l/∂e_{j+1} = F(e_{j+1})ᵀn, ∂l/∂e_j = −F(e_j)ᵀn.
  // L = (1 + ε_L)|d|, d = e_{j+1} − e_j: ∂L/∂e_{j+1} = −∂L/∂e_j = (1 + ε_L) d/|d|, ∂L/∂p = ε_L' |d|.
  const double area = model_.parameters().area();
  const double rest = 1 + model_.rest_strain(pressure_), rest_p = model_.parameters().rest_strain_slope;
  FiberParameterGradient g = zero_gradient();
  for (std::size_t j = 0; j < chords_.size(); ++j) {
    const SegmentState s = state(x, j);
    const MuscleDensity m = model_.density(pressure_, s.strain);
    const Eigen::Vector3d& d = segments_.vectors[j];
    const Eigen::Vector3d& n = s.direction;
    const double by_l = area * m.d_eps, by_L = area * (m.psi - m.d_eps * (1 + s.strain));
    const Eigen::Vector3d by_rest = by_L * rest * d.normalized();
    chain_to_parameters(j, -by_l * ends_[j].deformation_gradient(x).transpose() * n - by_rest,
                        by_l * ends_[j + 1].deformation_gradient(x).transpose() * n + by_rest, g);
    // ∂E_j/∂p = A L Ψ_p + ∂E_j/∂L ε_L' |d|
    g.pressure += area * s.rest_length * m.d_p + by_L * rest_p * d.norm();
  }
  return g;
}

FiberParameterGradient MuscleEnergy::mixed_derivative(const Eigen::VectorXd& x, const Eigen::VectorXd& lambda) const
{
  // φ = λ · ∂E/∂x = Σ_j A Ψ_ε(p, ε_j) q_j,  q = n · w,  u = x(e_{j+1}) − x(e_j),  w = λ(e_{j+1}) − λ(e_j),  l = |u|.
  // At an end e = e_{j+1} (s = +1) or e_j (s = −1), with F = F(e), G = Σ_i λ_i ∇N_i(e)ᵀ:
  //   ∂u/∂e = s F,  ∂w/∂e = s G,  ∂ε/∂e = s (Fᵀn − (1 + ε)(1 + ε_L) d/|d|) / L,
  //   ∂q/∂e = s (Fᵀ(w − q n) / l + Gᵀn),  ∂ε/∂p = −(1 + ε) ε_L' / (1 + ε_L).
  //   ∂φ_j = A [Ψ_εε q ∂ε + Ψ_ε ∂q] (+ A Ψ_εp q for p).
  const double area = model_.parameters().area();
  const double rest = 1 + model_.rest_strain(pressure_), rest_p = model_.parameters().rest_strain_slope;
  FiberParameterGradient g = zero_gradient();
  for (std::size_t j = 0; j < chords_.size(); ++j) {
    const SegmentState s = state(x, j);
    const MuscleDensity m = model_.density(pressure_, s.strain);
    const Chord& c = chords_[j];
    Eigen::Vector3d w = Eigen::Vector3d::Zero();
    for (std::size_t k = 0; k < c.nodes.size(); ++k)
      w += c.alpha[static_cast<Eigen::Index>(k)] * lambda.segment<3>(3 * c.nodes[k]);
    const Eigen::Vector3d& n = s.direction;
    const double q = n.dot(w), l = s.length, L = s.rest_length;
    const Eigen::Vector3d by_rest = (1 + s.strain) * rest * segments_.vectors[j].normalized();
    Eigen::Vector3d by_end[2];
    for (int end = 0; end < 2; ++end) {
      const ShapeEval& e = ends_[j + end];
      const Eigen::Matrix3d F = e.deformation_gradient(x), G = e.deformation_gradient(lambda);
      const double sign = end == 0 ? -1 : 1;
      const Eigen::Vector3d de = sign * (F.transpose() * n - by_rest) / L;
      const Eigen::Vector3d dq = sign * (F.transpose() * (w - q * n) / l + G.transpose() * n);
      by_end[end] = area * (m.d_eps_eps * q * de + m.d_eps * dq);
    }
    chain_to_parameters(j, by_end[0], by_end[1], g);
    const double de_dp = -(1 + s.strain) * rest_p / rest;
    g.pressure += area * (m.d_eps_p + m.d_eps_eps * de_dp) * q;
  }
  return g;
}

Eigen::MatrixXd MuscleEnergy::mixed_columns(const Eigen::VectorXd& x) const
{
  // mixed_derivative's by_end is linear in λ: at end e of segment j (sign s),
  //   by_e = A_e w + b_e Σ_{i at e} ∇N_i(e) (n · λ_i),
  //   A_e = A [Ψ_εε ∂ε nᵀ + Ψ_ε s Fᵀ(I − n nᵀ) / l],  b_e = A Ψ_ε s,  w = Σ_i α_i λ_i,
  // and the pressure's term is A (Ψ_εp + Ψ_εε ∂ε/∂p) nᵀw. Column (slot, c) of M gathers row c of
  // ∂by_e/∂λ times the spline weight of e on that slot.
  const double area = model_.parameters().area();
  const double rest = 1 + model_.rest_strain(pressure_), rest_p = model_.parameters().rest_strain_slope;
  const Eigen::Index points = static_cast<Eigen::Index>(spline_.points().size());
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(x.size(), 6 * points + 1);
  for (std::size_t j = 0; j < chords_.size(); ++j) {
    const SegmentState s = state(x, j);
    const MuscleDensity m = model_.density(pressure_, s.strain);
    const Chord& c = chords_[j];
    const Eigen::Vector3d& n = s.direction;
    const double l = s.length, L = s.rest_length;
    const Eigen::Vector3d by_rest = (1 + s.strain) * rest * segments_.vectors[j].normalized();
    const Eigen::Matrix3d across = Eigen::Matrix3d::Identity() - n * n.transpose();
    for (int end = 0; end < 2; ++end) {
      const ShapeEval& e = ends_[j + end];
      const Eigen::Matrix3d F = e.deformation_gradient(x);
      const double sign = end == 0 ? -1 : 1;
      const Eigen::Vector3d de = sign * (F.transpose() * n - by_rest) / L;
      const Eigen::Matrix3d A = area * (m.d_eps_eps * de * n.transpose() + m.d_eps * sign * F.transpose() * across / l);
      const double b = area * m.d_eps * sign;
      int k;
      double w[4];
      spline_.weights(segments_.t[j + end], k, w);
      const Eigen::Index slots[4] = {6 * k, 6 * k + 3, 6 * (k + 1), 6 * (k + 1) + 3};
      for (int slot = 0; slot < 4; ++slot)
        for (int r = 0; r < 3; ++r) {
          auto col = M.col(slots[slot] + r);
          for (std::size_t i = 0; i < c.nodes.size(); ++i)
            col.segment<3>(3 * c.nodes[i]) += w[slot] * c.alpha[static_cast<Eigen::Index>(i)] * A.row(r).transpose();
          for (Eigen::Index i = 0; i < e.size(); ++i) col.segment<3>(3 * e.nodes[i]) += w[slot] * b * e.dN(i, r) * n;
        }
    }
    const double de_dp = -(1 + s.strain) * rest_p / rest;
    const double by_pressure = area * (m.d_eps_p + m.d_eps_eps * de_dp);
    for (std::size_t i = 0; i < c.nodes.size(); ++i)
      M.col(6 * points).segment<3>(3 * c.nodes[i]) += by_pressure * c.alpha[static_cast<Eigen::Index>(i)] * n;
  }
  return M;
}

} // namespace fibermold
