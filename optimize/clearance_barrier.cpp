#include "optimize/clearance_barrier.hpp"

#include <cmath>

#include "core/units.hpp"
#include "optimize/barrier.hpp"

namespace fibermold {

ClearanceBarrier::ClearanceBarrier(const FiberClearance& measure, const std::vector<Route>& start, double clearance,
                                   double band)
    : measure_(measure), min_(clearance), band_(band)
{
  for (const auto& line : measure.lines(start)) {
    length_.emplace_back();
    for (std::size_t k = 0; k + 1 < line.size(); ++k)
      length_.back().push_back((line[k + 1] - line[k]).norm() / units::mm);
  }
}

double ClearanceBarrier::value(const std::vector<Route>& routes) const
{
  double B = 0;
  for (const Contact& c : measure_.contacts(measure_.lines(routes), min_ + band_, false)) {
    B += length_[c.a][c.segment_a] * barrier((c.clearance - min_) / band_, 1.0);
    if (!std::isfinite(B)) return HUGE_VAL;
  }
  return B;
}

std::vector<FiberParameterGradient> ClearanceBarrier::gradient(const std::vector<Route>& routes, int only) const
{
  std::vector<FiberParameterGradient> g(routes.size());
  std::vector<HermiteSpline> splines;
  for (std::size_t f = 0; f < routes.size(); ++f) {
    g[f].points.assign(routes[f].points.size(), Eigen::Vector3d::Zero());
    g[f].tangents.assign(routes[f].points.size(), Eigen::Vector3d::Zero());
    splines.emplace_back(routes[f].points, routes[f].tangents);
  }
  // Adds `by_p` · ∂(sample k of fiber f)/∂(parameters), scaled by `w`.
  const auto add_sample = [&](int f, int k, double w, const Eigen::Vector3d& by_p) {
    int span;
    double h[4];
    splines[f].weights(measure_.parameters(f)[k], span, h);
    g[f].points[span] += w * h[0] * by_p;
    g[f].tangents[span] += w * h[1] * by_p;
    g[f].points[span + 1] += w * h[2] * by_p;
    g[f].tangents[span + 1] += w * h[3] * by_p;
  };
  for (const Contact& c : measure_.contacts(measure_.lines(routes), min_ + band_, false, only)) {
    if (c.clearance <= min_) continue;
    const Eigen::Vector3d by_p =
        length_[c.a][c.segment_a] * barrier_gradient((c.clearance - min_) / band_, 1.0) / band_ * c.normal;
    add_sample(c.a, c.segment_a, 1 - c.u_a, by_p);
    add_sample(c.a, c.segment_a + 1, c.u_a, by_p);
    add_sample(c.b, c.segment_b, -(1 - c.u_b), by_p);
    add_sample(c.b, c.segment_b + 1, -c.u_b, by_p);
  }
  return g;
}

} // namespace fibermold
