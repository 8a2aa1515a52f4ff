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
  /// `target`: the target's nodal state x̂ (3n).
  DistanceObjective(const Basis& basis, std::vector<TrackingSamples> curves, const Eigen::VectorXd& target);

  double value(const Eigen::VectorXd& x) const;
  /// ∂f/∂x_i = w_pos (x(q) − x̂(q)) N_i(q) + w_ori (F − F̂) ∇N_i(q), summed over samples.
  Eigen::VectorXd gradient(const Eigen::VectorXd& x) const;

  /// Root-mean-square and largest position error over all samples (m).
  double rmse(const Eigen::VectorXd& x) const;
  double max_error(const Eigen::VectorXd& x) const;

private:
  struct Sample {
    ShapeEval at;
    Eigen::Vector3d target_position;
    Eigen::Matrix3d target_gradient;
    double w_pos, w_ori;
  };
  std::vector<Sample> samples_;
};

} // namespace fibermold
