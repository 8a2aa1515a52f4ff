#pragma once
// The actuation energy of one muscle fiber (paper eq. 2, discretized by eq. 10):
//   E_act = Σ_j Ψ_act(p, ε_j) A_act L_j,   L_j = (ε_L(p) + 1) |d_j|,   l_j = |F(c_j) d_j|,
//   ε_j = l_j / L_j − 1,
// with the deformation gradient F evaluated at each straight segment's centre c_j. Besides the
// derivatives in x for Newton, it gives those in the spline's points and tangents and in the
// pressure, for the adjoint gradient of eq. 9.

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
  /// and their first two derivatives are evaluated at the segment centres once.
  MuscleEnergy(const Basis& basis, const MuscleModel& model, HermiteSpline spline, std::vector<double> t, double pressure);

  std::string name() const override { return "muscle"; }
  double value(const Eigen::VectorXd& x) const override;
  void add_gradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const override;
  void add_hessian(const Eigen::VectorXd& x, SparseHessian& H, bool project) const override;
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

private:
  struct SegmentState {
    double rest_length, length, strain;  ///< L_j, l_j, ε_j
    Eigen::Vector3d direction;           ///< n = F d / l
  };
  SegmentState state(const Eigen::VectorXd& x, std::size_t j) const;
  /// Adds a derivative with respect to segment j's vector d_j and centre c_j to the spline's parameters.
  void chain_to_parameters(std::size_t j, const Eigen::Vector3d& by_d, const Eigen::Vector3d& by_c,
                           FiberParameterGradient& out) const;
  FiberParameterGradient zero_gradient() const;
  Eigen::Matrix3d centre_derivative(const Eigen::VectorXd& v, std::size_t j) const;

  const MuscleModel& model_;
  HermiteSpline spline_;
  FiberSegments segments_;
  std::vector<ShapeEval> at_;           ///< shape functions at c_j, with ∇∇N
  std::vector<Eigen::VectorXd> alpha_;  ///< α_i = ∇N_i(c_j) · d_j
  double pressure_;
};

} // namespace fibermold
