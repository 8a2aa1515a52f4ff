#include "optimize/distance_objective.hpp"

#include <algorithm>
#include <cmath>

#include "core/units.hpp"
#include "sim/rigid_motion.hpp"

namespace fibermold {

DistanceObjective::DistanceObjective(const Basis& basis, std::vector<TrackingSamples> curves,
                                     const Eigen::VectorXd& target, double weight)
{
  for (const TrackingSamples& c : curves)
    for (const Eigen::Vector3d& q : c.points) {
      Sample s{basis.at(q, 1), {}, {}, c.weight_position, c.weight_orientation, c.weight_orientation > 0};
      s.target_position = s.at.position(target);
      s.target_gradient = s.at.deformation_gradient(target);
      samples_.push_back(std::move(s));
    }
  // Per-sample weights carry the normalisation of the header's formula, and the target's weight.
  const double per_sample = samples_.empty() ? 0 : weight / static_cast<double>(samples_.size());
  for (Sample& s : samples_) {
    s.w_pos *= per_sample / (units::mm * units::mm);
    s.w_ori *= per_sample;
  }
}

double DistanceObjective::value(const Eigen::VectorXd& x) const
{
  double f = 0;
  for (const Sample& s : samples_)
    f += s.w_pos / 2 * (s.at.position(x) - s.target_position).squaredNorm() +
         s.w_ori / 2 * (s.at.deformation_gradient(x) - s.target_gradient).squaredNorm();
  return f;
}

Eigen::VectorXd DistanceObjective::gradient(const Eigen::VectorXd& x) const
{
  Eigen::VectorXd g = Eigen::VectorXd::Zero(x.size());
  for (const Sample& s : samples_) {
    const Eigen::Vector3d dp = s.w_pos * (s.at.position(x) - s.target_position);
    const Eigen::Matrix3d dF = s.w_ori * (s.at.deformation_gradient(x) - s.target_gradient);
    for (Eigen::Index k = 0; k < s.at.size(); ++k)
      g.segment<3>(3 * s.at.nodes[k]) += s.at.N[k] * dp + dF * s.at.dN.row(k).transpose();
  }
  return g;
}

Eigen::MatrixXd DistanceObjective::gauss_newton_hessian(const Eigen::MatrixXd& S) const
{
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(S.cols(), S.cols());
  Eigen::MatrixXd P(3, S.cols()), R(9, S.cols());
  for (const Sample& s : samples_) {
    P.setZero();
    R.setZero();
    for (Eigen::Index k = 0; k < s.at.size(); ++k) {
      const auto Sk = S.middleRows(3 * s.at.nodes[k], 3);
      P += s.at.N[k] * Sk;
      if (s.w_ori != 0)
        for (int b = 0; b < 3; ++b) R.middleRows(3 * b, 3) += s.at.dN(k, b) * Sk;
    }
    H.selfadjointView<Eigen::Lower>().rankUpdate(P.transpose(), s.w_pos);
    if (s.w_ori != 0) H.selfadjointView<Eigen::Lower>().rankUpdate(R.transpose(), s.w_ori);
  }
  return H.selfadjointView<Eigen::Lower>();
}

double DistanceObjective::rmse(const Eigen::VectorXd& x) const
{
  double sum = 0;
  for (const Sample& s : samples_) sum += (s.at.position(x) - s.target_position).squaredNorm();
  return samples_.empty() ? 0 : std::sqrt(sum / static_cast<double>(samples_.size()));
}

double DistanceObjective::max_error(const Eigen::VectorXd& x) const
{
  double worst = 0;
  for (const Sample& s : samples_) worst = std::max(worst, (s.at.position(x) - s.target_position).norm());
  return worst;
}

bool DistanceObjective::tracks_orientation() const
{
  return std::any_of(samples_.begin(), samples_.end(), [](const Sample& s) { return s.orientation_tracked; });
}

double DistanceObjective::orientation_error(const Sample& s, const Eigen::VectorXd& x)
{
  const Eigen::Matrix3d turned = polar_rotation(s.at.deformation_gradient(x));
  const Eigen::Matrix3d asked = polar_rotation(s.target_gradient);
  return RigidMotion{turned * asked.transpose(), Eigen::Vector3d::Zero()}.angle();
}

DistanceObjective::OrientationErrors DistanceObjective::orientation_errors(const Eigen::VectorXd& x) const
{
  OrientationErrors e;
  double sum = 0;
  int count = 0;
  for (const Sample& s : samples_)
    if (s.orientation_tracked) {
      const double angle = orientation_error(s, x);
      sum += angle * angle;
      e.max = std::max(e.max, angle);
      ++count;
    }
  e.rms = count == 0 ? 0 : std::sqrt(sum / count);
  return e;
}

} // namespace fibermold
