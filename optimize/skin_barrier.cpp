#include "optimize/skin_barrier.hpp"

#include <cmath>

#include "optimize/barrier.hpp"

namespace fibermold {

std::vector<double> parameters_off_exits(const SurfaceDistance& skin, const HermiteSpline& spline,
                                         const std::vector<double>& t, double reach)
{
  const double length = spline.length();
  const bool first_on_skin = skin.closest(spline.points().front()).distance < reach;
  const bool last_on_skin = skin.closest(spline.points().back()).distance < reach;
  std::vector<double> kept;
  // Arc length at each parameter, from the chords (fine enough to place the cut-off).
  double s = 0;
  for (std::size_t k = 0; k < t.size(); ++k) {
    if (k > 0) s += (spline.position(t[k]) - spline.position(t[k - 1])).norm();
    if (first_on_skin && s < 2 * reach) continue;
    if (last_on_skin && length - s < 2 * reach) continue;
    kept.push_back(t[k]);
  }
  return kept;
}

SkinBarrier::SkinBarrier(const SurfaceDistance& skin, double min_distance, double band, const HermiteSpline& initial,
                         int samples)
    : skin_(skin), min_(min_distance), band_(band), t_(parameters_off_exits(skin, initial, segment_parameters(initial, samples), min_distance + band))
{
}

double SkinBarrier::value(const HermiteSpline& spline) const
{
  double B = 0;
  for (double t : t_) {
    const auto c = skin_.closest(spline.position(t));
    if (!c.inside) return HUGE_VAL;
    B += barrier((c.distance - min_) / band_, 1.0);
  }
  return B;
}

FiberParameterGradient SkinBarrier::gradient(const HermiteSpline& spline) const
{
  FiberParameterGradient g;
  g.points.assign(spline.points().size(), Eigen::Vector3d::Zero());
  g.tangents.assign(spline.points().size(), Eigen::Vector3d::Zero());
  for (double t : t_) {
    const Eigen::Vector3d p = spline.position(t);
    const auto c = skin_.closest(p);
    if (!c.inside || c.distance >= min_ + band_) continue;
    // ∂b/∂p = b'((d − d_min)/w)/w ∇d,  ∇d = (p − c)/|p − c| inside the body
    const Eigen::Vector3d by_p = barrier_gradient((c.distance - min_) / band_, 1.0) / band_ * (p - c.point) / c.distance;
    int k;
    double w[4];
    spline.weights(t, k, w);
    g.points[k] += w[0] * by_p;
    g.tangents[k] += w[1] * by_p;
    g.points[k + 1] += w[2] * by_p;
    g.tangents[k + 1] += w[3] * by_p;
  }
  return g;
}

double SkinBarrier::closest_approach(const HermiteSpline& spline, Eigen::Vector3d& where) const
{
  double d = HUGE_VAL;
  for (double t : t_) {
    const Eigen::Vector3d p = spline.position(t);
    const auto c = skin_.closest(p);
    if (const double signed_d = c.inside ? c.distance : -c.distance; signed_d < d) {
      d = signed_d;
      where = p;
    }
  }
  return d;
}

} // namespace fibermold
