#pragma once
// The actuation energy of one muscle fiber (paper eq. 2, discretized by eq. 10):
//   E_act = Σ_j Ψ_act(p, ε_j) A_act L_j,   L_j = (ε_L(p) + 1) |d_j|,   l_j = |F(c_j) d_j|,
//   ε_j = l_j / L_j − 1,
// with the deformation gradient F evaluated at each straight segment's centre c_j.

#include "sim/energy.hpp"
#include "sim/hermite_spline.hpp"
#include "sim/muscle_model.hpp"
#include "sim/shape_functions.hpp"

namespace fibermold {

class MuscleEnergy final : public Energy {
public:
  /// Shape functions are evaluated at the segment centres once (the fiber does not move during a solve).
  MuscleEnergy(const Basis& basis, const MuscleModel& model, FiberSegments segments, double pressure);

  std::string name() const override { return "muscle"; }
  double value(const Eigen::VectorXd& x) const override;
  void add_gradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const override;
  void add_hessian(const Eigen::VectorXd& x, SparseHessian& H, bool project) const override;
  void stencils(std::vector<std::vector<int>>& out) const override;

  void set_pressure(double p) { pressure_ = p; }
  double pressure() const { return pressure_; }
  const FiberSegments& segments() const { return segments_; }
  /// ε_j at state x.
  std::vector<double> strains(const Eigen::VectorXd& x) const;

private:
  struct SegmentState {
    double rest_length, length, strain;  ///< L_j, l_j, ε_j
    Eigen::Vector3d direction;           ///< n = F d / l
  };
  SegmentState state(const Eigen::VectorXd& x, std::size_t j) const;

  const MuscleModel& model_;
  FiberSegments segments_;
  std::vector<ShapeEval> at_;      ///< shape functions at c_j
  std::vector<Eigen::VectorXd> alpha_;  ///< α_i = ∇N_i(c_j) · d_j
  double pressure_;
};

} // namespace fibermold
