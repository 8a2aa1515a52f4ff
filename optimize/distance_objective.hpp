#pragma once
// The distance to a target along the tracking curves (paper section V-A):
//   f_dist = (1/J) Σ_j [ w_pos ½ |x(q_j) − x̂(q_j)|² / ℓ² + w_ori ½ ‖F(q_j) − F̂(q_j)‖²_F ]
// (the frames A_j drop out of the second term: ‖D A_j‖_F = ‖D‖_F for orthonormal A_j).
// Unlike the paper's sum, positions are measured in ℓ = 1 mm and the sum is averaged over the J
// samples, so that the weights mean the same whatever the body's size and the sample count:
// f_dist = ½ RMSE² in mm² when only positions are tracked.

#include <vector>

#include <Eigen/Core>

#include "optimize/tracking_curve.hpp"
#include "sim/shape_functions.hpp"

namespace fibermold {

class DistanceObjective {
public:
  /// `target`: the target's nodal state x̂ (3n); `weight` multiplies f_dist (the target's weight in eq. 4).
  DistanceObjective(const Basis& basis, std::vector<TrackingSamples> curves, const Eigen::VectorXd& target,
                    double weight = 1);

  double value(const Eigen::VectorXd& x) const;
  /// ∂f/∂x_i = w_pos (x(q) − x̂(q)) N_i(q) + w_ori (F − F̂) ∇N_i(q), summed over samples.
  Eigen::VectorXd gradient(const Eigen::VectorXd& x) const;
  /// Sᵀ ∇²f S for the sensitivities S = dx/dz (3n × m): f_dist is quadratic in x, so this is the
  /// Gauss-Newton Hessian of f_dist(x(z)) in z: Σ_j w_pos PᵀP + w_ori Σ_ab R_abᵀR_ab, with P = Σ_i N_i S_i
  /// (S_i: node i's 3 rows) and R_ab = Σ_i ∂_b N_i S_{i,a}.
  Eigen::MatrixXd gauss_newton_hessian(const Eigen::MatrixXd& S) const;

  /// Root-mean-square and largest position error over all samples (m).
  double rmse(const Eigen::VectorXd& x) const;
  double max_error(const Eigen::VectorXd& x) const;

  /// Whether any sample's orientation is tracked (its curve's weight_orientation > 0).
  bool tracks_orientation() const;
  /// Root-mean-square and largest angle (rad) between how the material turned and how the target's
  /// turned, over the samples whose orientation is tracked: the angle of R R̂ᵀ, R and R̂ the rotations
  /// of F = R U and F̂ = R̂ Û. A twist moves a bar's centreline little and turns it much; these say
  /// how far the turn is from the one asked, which the position errors above leave out. 0 when no
  /// sample's orientation is tracked.
  struct OrientationErrors {
    double rms = 0, max = 0;
  };
  OrientationErrors orientation_errors(const Eigen::VectorXd& x) const;

private:
  struct Sample {
    ShapeEval at;
    Eigen::Vector3d target_position;
    Eigen::Matrix3d target_gradient;
    double w_pos, w_ori;
    bool orientation_tracked;
  };
  /// The angle of sample s's turn from its target's (rad).
  static double orientation_error(const Sample& s, const Eigen::VectorXd& x);
  std::vector<Sample> samples_;
};

} // namespace fibermold
