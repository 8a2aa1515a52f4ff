#pragma once
// The actuation energy of one muscle fiber (paper eq. 2, discretized as eq. 10):
//   E_act = Σ_j Ψ_act(p, ε_j) A_act L_j,   L_j = (ε_L(p) + 1) |d_j|,   l_j = |x(e_{j+1}) − x(e_j)|,
//   ε_j = l_j / L_j − 1,
// where e_j, e_{j+1} are straight segment j's ends and x(X) = Σ_i x_i N_i(X) the deformed position.
// The paper takes l_j = |F(c_j) d_j|, the deformation gradient at the segment's centre: the same for
// a uniform F, but a mesh finer than the segments can then meet the muscle by compressing the body
// at the segment centres alone (on a bar 129 mm long, the straight muscle's contraction at 300 kPa
// fell from 12.9 to 3.9 mm as the edges went from 10 to 2.6 mm; fem-p2, to 0.15 mm). The deformed
// chord is the length of the body's line between the ends, so the segments' lengths add up along
// the fiber: the same bar gives 12.9, 12.6, 12.5, 12.3 mm (docs/sim.md, "The muscle's deformed length").
// Besides the derivatives in x for Newton, it gives those in the spline's points and tangents and in
// the pressure, for the adjoint gradient of eq. 9.

#include "sim/energy.hpp"
#include "sim/hermite_spline.hpp"
#include "sim/muscle_model.hpp"
#include "sim/shape_functions.hpp"

namespace fibermold {

/// A derivative with respect to a fiber's parameters: one 3-vector per control point and per
/// tangent, and one number for the pressure.
struct FiberParameterGradient {
  std::vector<Eigen::Vector3d> points, tangents;
  double pressure = 0;
};

class MuscleEnergy final : public Energy {
public:
  /// Segments between the spline parameters `t` (held fixed as the spline moves). Shape functions
  /// and their gradients are evaluated at the segments' ends once.
  MuscleEnergy(const Basis& basis, const MuscleModel& model, HermiteSpline spline, std::vector<double> t,
               double pressure);

  std::string name() const override { return "muscle"; }
  double value(const Eigen::VectorXd& x) const override;
  void add_gradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const override;
  void add_hessian(const Eigen::VectorXd& x, SparseHessian& H, bool project) const override;
  /// In closed form: the exact Hessian's product, chord by chord (no lumped pairs).
  void add_hessian_product(const Eigen::VectorXd& x, const Eigen::VectorXd& v, Eigen::VectorXd& out) const override;
  std::unique_ptr<HessianProduct> hessian_at(const Eigen::VectorXd& x) const override;
  void stencils(std::vector<std::vector<int>>& out) const override;

  double pressure() const { return pressure_; }
  const HermiteSpline& spline() const { return spline_; }
  const FiberSegments& segments() const { return segments_; }
  /// ε_j at state x.
  std::vector<double> strains(const Eigen::VectorXd& x) const;

  /// ∂E_act/∂(points, tangents, p) at fixed x.
  FiberParameterGradient parameter_gradient(const Eigen::VectorXd& x) const;
  /// ∂/∂(points, tangents, p) of λ · ∂E_act/∂x at fixed x: the mixed term λᵀ ∂²E/∂x∂(s, p) of the
  /// adjoint (eq. 9), without forming the matrix.
  FiberParameterGradient mixed_derivative(const Eigen::VectorXd& x, const Eigen::VectorXd& lambda) const;
  /// The matrix M = ∂²E_act/∂x∂(s, p) itself (rows: x; columns: 6k + c for point k's component c,
  /// 6k + 3 + c for tangent k's, 6·(points) for the pressure), so that Mᵀλ is mixed_derivative(x, λ):
  /// the right-hand sides of the forward sensitivities dx*/d(s, p) = −H⁻¹M.
  Eigen::MatrixXd mixed_columns(const Eigen::VectorXd& x) const;

private:
  struct SegmentState {
    double rest_length, length, strain; ///< L_j, l_j, ε_j
    Eigen::Vector3d direction;          ///< n = u / l,  u = x(e_{j+1}) − x(e_j)
  };
  /// Segment j's deformed chord u = Σ_i α_i x_i, α_i = N_i(e_{j+1}) − N_i(e_j), over the nodes of
  /// either end.
  struct Chord {
    std::vector<int> nodes;
    Eigen::VectorXd alpha;
  };
  SegmentState state(const Eigen::VectorXd& x, std::size_t j) const;
  /// ∂²E/∂u² of segment j's energy in its deformed chord u (3 × 3), eigenvalues projected to ≥ 0
  /// with `project`: the Hessian's block between nodes i and k is α_i α_k times it.
  Eigen::Matrix3d chord_hessian(const Eigen::VectorXd& x, std::size_t j, bool project) const;
  /// Adds a derivative with respect to segment j's ends e_j and e_{j+1} to the spline's parameters.
  void chain_to_parameters(std::size_t j, const Eigen::Vector3d& by_start, const Eigen::Vector3d& by_end,
                           FiberParameterGradient& out) const;
  FiberParameterGradient zero_gradient() const;

  const MuscleModel& model_;
  HermiteSpline spline_;
  FiberSegments segments_;
  std::vector<ShapeEval> ends_; ///< shape functions at the segments' ends e_0 … e_n, with ∇N
  std::vector<Chord> chords_;
  double pressure_;
};

} // namespace fibermold
