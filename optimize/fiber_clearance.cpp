#include "optimize/fiber_clearance.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <stdexcept>

#include <Eigen/Geometry>
#include <fmt/format.h>
#include <nanoflann.hpp>
#include <tbb/parallel_for.h>

#include "optimize/skin_barrier.hpp"

namespace fibermold {

namespace {

constexpr double kEpsilon = 1e-12;

HermiteSpline spline_of(const Route& r) { return HermiteSpline(r.points, r.tangents); }

/// A unit vector normal to `d`.
Eigen::Vector3d any_normal(const Eigen::Vector3d& d)
{
  const Eigen::Vector3d axis = std::abs(d.x()) < 0.9 * d.norm() ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  return d.cross(axis).normalized();
}

} // namespace

void closest_points_of_segments(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& q0,
                                const Eigen::Vector3d& q1, double& s, double& t)
{
  const Eigen::Vector3d d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  if (a <= kEpsilon && e <= kEpsilon) {
    s = t = 0;
    return;
  }
  if (a <= kEpsilon) {
    s = 0;
    t = std::clamp(f / e, 0.0, 1.0);
    return;
  }
  const double c = d1.dot(r);
  if (e <= kEpsilon) {
    t = 0;
    s = std::clamp(-c / a, 0.0, 1.0);
    return;
  }
  const double b = d1.dot(d2), denominator = a * e - b * b;
  s = denominator > kEpsilon * a * e ? std::clamp((b * f - c * e) / denominator, 0.0, 1.0) : 0.0;
  t = (b * s + f) / e;
  if (t < 0) {
    t = 0;
    s = std::clamp(-c / a, 0.0, 1.0);
  } else if (t > 1) {
    t = 1;
    s = std::clamp((b - c) / a, 0.0, 1.0);
  }
}

double smallest_clearance(const std::vector<Contact>& contacts)
{
  double m = HUGE_VAL;
  for (const Contact& c : contacts) m = std::min(m, c.clearance);
  return m;
}

FiberClearance::FiberClearance(const SurfaceDistance& skin, const std::vector<Route>& routes, double radius,
                               double clearance, double samples_per_length, double skin_margin,
                               const std::vector<HeldStretch>& held)
    : skin_(skin), radius_(radius), skin_margin_(skin_margin)
{
  if (!held.empty() && held.size() != routes.size())
    throw std::invalid_argument(
        fmt::format("FiberClearance: {} held stretches for {} fibers", held.size(), routes.size()));
  for (std::size_t f = 0; f < routes.size(); ++f) {
    const HermiteSpline s = spline_of(routes[f]);
    const int count = std::max(8, static_cast<int>(std::ceil(s.length() * samples_per_length)));
    t_.push_back(segment_parameters(s, count));
    std::vector<bool> is_tested;
    if (!held.empty()) {
      for (double t : t_.back()) is_tested.push_back(held[f].holds(t));
    } else {
      const std::vector<double> tested = parameters_off_exits(skin, s, t_.back(), 2 * radius + clearance);
      for (double t : t_.back()) is_tested.push_back(std::binary_search(tested.begin(), tested.end(), t));
    }
    skin_tested_.push_back(std::move(is_tested));
  }
}

FiberClearance::Lines FiberClearance::lines(const std::vector<Route>& routes) const
{
  Lines out(t_.size());
  for (std::size_t f = 0; f < t_.size(); ++f) {
    const HermiteSpline s = spline_of(routes[f]);
    out[f].reserve(t_[f].size());
    for (double t : t_[f]) out[f].push_back(s.position(t));
  }
  return out;
}

Contact FiberClearance::skin_contact(const std::vector<Eigen::Vector3d>& line, int a, int k) const
{
  Contact c;
  c.a = a;
  c.segment_a = k;
  c.point_a = line[k];
  const auto at = skin_.closest(line[k]);
  c.point_b = at.point;
  c.clearance = (at.inside ? at.distance : -at.distance) - radius_ - skin_margin_;
  if (at.distance > kEpsilon) {
    c.normal = (at.inside ? 1.0 : -1.0) * (line[k] - at.point) / at.distance;
  } else { // on the skin: the gradient of the signed distance, by central differences
    const double h = 1e-6;
    for (int i = 0; i < 3; ++i) {
      const auto signed_at = [&](double step) {
        const auto q = skin_.closest(line[k] + step * Eigen::Vector3d::Unit(i));
        return q.inside ? q.distance : -q.distance;
      };
      c.normal[i] = (signed_at(h) - signed_at(-h)) / (2 * h);
    }
    c.normal.normalize();
  }
  return c;
}

namespace {

Contact pair_contact(const std::vector<Eigen::Vector3d>& la, int a, int i, const std::vector<Eigen::Vector3d>& lb,
                     int b, int j, double radius)
{
  Contact c;
  c.a = a;
  c.b = b;
  c.segment_a = i;
  c.segment_b = j;
  closest_points_of_segments(la[i], la[i + 1], lb[j], lb[j + 1], c.u_a, c.u_b);
  c.point_a = la[i] + c.u_a * (la[i + 1] - la[i]);
  c.point_b = lb[j] + c.u_b * (lb[j + 1] - lb[j]);
  const Eigen::Vector3d gap = c.point_a - c.point_b;
  const double distance = gap.norm();
  c.clearance = distance - 2 * radius;
  if (distance > kEpsilon) {
    c.normal = gap / distance;
  } else { // the centre lines cross: part them across both
    const Eigen::Vector3d across = (la[i + 1] - la[i]).cross(lb[j + 1] - lb[j]);
    c.normal = across.norm() > kEpsilon ? across.normalized() : any_normal(la[i + 1] - la[i]);
  }
  return c;
}

} // namespace

std::vector<Contact> FiberClearance::contacts(const Lines& lines, double below, bool skin, int only) const
{
  const int F = num_fibers();
  // Every sample (skin) and every segment (pairs) is measured on its own, in parallel, into its
  // own slot; the slots are joined in order, so that the result does not depend on the threads.
  std::vector<std::pair<int, int>> samples; // (fiber, sample) tested against the skin
  for (int a = 0; a < F && skin; ++a)
    for (int k = 0; k < static_cast<int>(lines[a].size()); ++k)
      if (skin_tested_[a][k]) samples.emplace_back(a, k);
  std::vector<std::optional<Contact>> on_skin(samples.size());
  tbb::parallel_for(std::size_t{0}, samples.size(), [&](std::size_t n) {
    const auto [a, k] = samples[n];
    if (Contact c = skin_contact(lines[a], a, k); c.clearance < below) on_skin[n] = c;
  });
  std::vector<Contact> out;
  for (const auto& c : on_skin)
    if (c) out.push_back(*c);
  if (F < 2) return out;

  // Broad phase: segments by their midpoints.
  std::vector<std::pair<int, int>> owner; // (fiber, segment)
  for (int f = 0; f < F; ++f)
    for (int k = 0; k + 1 < static_cast<int>(lines[f].size()); ++k) owner.emplace_back(f, k);
  Eigen::MatrixX3d mids(static_cast<Eigen::Index>(owner.size()), 3);
  double longest = 0;
  for (std::size_t n = 0; n < owner.size(); ++n) {
    const auto [f, k] = owner[n];
    mids.row(static_cast<Eigen::Index>(n)) = (0.5 * (lines[f][k] + lines[f][k + 1])).transpose();
    longest = std::max(longest, (lines[f][k + 1] - lines[f][k]).norm());
  }
  const nanoflann::KDTreeEigenMatrixAdaptor<Eigen::MatrixX3d> tree(3, std::cref(mids), 16);
  const double reach = std::max(0.0, below) + 2 * radius_ + longest;
  std::vector<std::vector<Contact>> between(owner.size());
  tbb::parallel_for(std::size_t{0}, owner.size(), [&](std::size_t n) {
    const auto [a, i] = owner[n];
    if (only >= 0 && a > only) return; // its pairs are with fibers after it
    const Eigen::Vector3d m = mids.row(static_cast<Eigen::Index>(n)).transpose();
    std::vector<std::pair<Eigen::Index, double>> found;
    tree.index->radiusSearch(m.data(), reach * reach, found, nanoflann::SearchParams(32, 0, false));
    std::map<int, Contact> closest; // per other fiber
    for (const auto& [index, squared] : found) {
      const auto [b, j] = owner[static_cast<std::size_t>(index)];
      if (b <= a || (only >= 0 && a != only && b != only)) continue;
      const Contact c = pair_contact(lines[a], a, i, lines[b], b, j, radius_);
      if (auto it = closest.find(b); it == closest.end() || c.clearance < it->second.clearance) closest[b] = c;
    }
    for (const auto& [b, c] : closest)
      if (c.clearance < below) between[n].push_back(c);
  });
  for (const auto& contacts : between) out.insert(out.end(), contacts.begin(), contacts.end());
  return out;
}

Contact FiberClearance::remeasure(const Lines& lines, int a, int k, int b) const
{
  const std::vector<Eigen::Vector3d>& la = lines[a];
  if (b < 0) return skin_contact(la, a, k);
  const std::vector<Eigen::Vector3d>& lb = lines[b];
  Contact best;
  best.clearance = HUGE_VAL;
  for (int j = 0; j + 1 < static_cast<int>(lb.size()); ++j)
    if (Contact c = pair_contact(la, a, k, lb, b, j, radius_); c.clearance < best.clearance) best = c;
  return best;
}

} // namespace fibermold
