#pragma once
// The clearance measure of the collide stage: how much room each muscle has, between every pair of
// fibers (the distance between their centre lines minus both muscle radii) and between each fiber
// and the skin (the distance to the undeformed surface minus the radius; negative outside).
//
// Each centre line is sampled densely at spline parameters fixed on the starting routing, so that a
// sample moves linearly with the control points and tangents; distances are taken between the
// polylines through the samples (exact segment–segment closest points), with a kd-tree over the
// segments' midpoints as broad phase. Near an end that lies on the skin, where the fiber leaves
// the body by design, the skin is not tested (the stretch the optimizer's skin barrier leaves out).

#include <vector>

#include "optimize/skin_barrier.hpp"

#include <Eigen/Core>

#include "mesh/surface_distance.hpp"
#include "optimize/routing.hpp"

namespace fibermold {

/// Where two fibers, or a fiber and the skin, come closest.
struct Contact {
  int a = -1, b = -1;               ///< fibers; b = −1: the skin
  int segment_a = 0, segment_b = 0; ///< sample segments (k: between samples k and k+1); skin: the sample
  double u_a = 0, u_b = 0;          ///< where along them, in [0, 1]
  Eigen::Vector3d point_a, point_b; ///< the closest points; b on the skin
  Eigen::Vector3d normal;           ///< unit: the clearance grows as a moves along it and b against it
  double clearance = 0;             ///< surface to surface, m (negative: overlap)

  bool with_skin() const { return b < 0; }
};

class FiberClearance {
public:
  /// `radius`: the muscle's (m); `clearance`: the clearance asked for, which, without `held`, sets
  /// how much of an end on the skin is not tested: 2 (2 radius + clearance) of arc;
  /// `samples_per_length`: centre-line samples per m (at least 8 per fiber); `skin_margin` (m):
  /// how much further than the clearance the skin is kept from the muscle (a groove that needs
  /// more room): a skin contact's clearance is its distance − radius − skin_margin. `held`: per
  /// fiber, the parameters the optimizer's skin barrier held (SkinBarrier::held): the skin is
  /// tested there alone.
  FiberClearance(const SurfaceDistance& skin, const std::vector<Route>& routes, double radius, double clearance,
                 double samples_per_length, double skin_margin = 0, const std::vector<HeldStretch>& held = {});

  int num_fibers() const { return static_cast<int>(t_.size()); }
  double radius() const { return radius_; }
  /// Sample parameters of fiber f, and whether each is tested against the skin.
  const std::vector<double>& parameters(int f) const { return t_[f]; }
  const std::vector<bool>& skin_tested(int f) const { return skin_tested_[f]; }
  /// The sample polyline of every fiber at `routes` (the same parameters as at construction).
  using Lines = std::vector<std::vector<Eigen::Vector3d>>;
  Lines lines(const std::vector<Route>& routes) const;

  /// Every place whose clearance is below `below` (m): for each sample segment of a fiber, the
  /// closest segment of each fiber after it; for each tested sample, the skin (unless `skin` is false).
  /// With `only` ≥ 0, of the pairs of fibers those that include fiber `only` alone (the skin's all).
  std::vector<Contact> contacts(const Lines& lines, double below, bool skin = true, int only = -1) const;
  std::vector<Contact> contacts(const std::vector<Route>& routes, double below) const
  {
    return contacts(lines(routes), below);
  }
  /// The closest place between segment k of fiber a and fiber b (any segment), or sample k of a
  /// and the skin (b = −1): a contact found before, measured again after the routes moved.
  Contact remeasure(const Lines& lines, int a, int k, int b) const;

private:
  Contact skin_contact(const std::vector<Eigen::Vector3d>& line, int a, int k) const;

  const SurfaceDistance& skin_;
  double radius_;
  double skin_margin_ = 0;
  std::vector<std::vector<double>> t_;
  std::vector<std::vector<bool>> skin_tested_;
};

/// The closest points of segments [p0, p1] and [q0, q1]: p0 + s (p1 − p0) and q0 + t (q1 − q0)
/// with s, t ∈ [0, 1] (Ericson, Real-Time Collision Detection, 5.1.9).
void closest_points_of_segments(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& q0,
                                const Eigen::Vector3d& q1, double& s, double& t);

/// The smallest clearance among `contacts` (+∞ when there are none).
double smallest_clearance(const std::vector<Contact>& contacts);

} // namespace fibermold
