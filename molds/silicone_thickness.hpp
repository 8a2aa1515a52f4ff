#pragma once
// How thin the cast silicone gets where the grooves run: shot 1's cast between a groove's walls
// and the skin (a groove passing a notch or the body's side leaves a web there), and shot 2's
// overmold over each laid muscle, from the muscle's top up to the skin. A web much thinner than a
// millimetre tears on demolding or when the muscle inflates.

#include <cmath>
#include <vector>

#include <Eigen/Core>

#include "mesh/surface_distance.hpp"
#include "mesh/surface_mesh.hpp"

namespace fibermold {

/// m: shot 1's webs thicker than this are not measured (a groove wall whose skin is farther).
inline constexpr double kThickestMeasuredWeb = 2e-3;

struct SiliconeThickness {
  /// m: the thinnest shot-1 silicone between a groove's walls (more than its radius below its
  /// mouth) and the skin; below kThickestMeasuredWeb, else +∞
  double groove_web = HUGE_VAL;
  Eigen::Vector3d groove_web_at = Eigen::Vector3d::Zero();
  double overmold = HUGE_VAL; ///< m: the thinnest shot-2 silicone over a muscle; +∞ where none is measured
  Eigen::Vector3d overmold_at = Eigen::Vector3d::Zero();
};

/// The arc (m) at each end of a fiber where it leaves the body by design: the stretches the
/// optimizer's skin barrier left out (0 at an end inside the body), measured along the fiber as
/// routed. The molds' route check and the silicone's thickness leave them out, as collide does.
struct ExitStretches {
  double first = 0, last = 0;
};

/// Per point of a fiber's polyline: whether it lies beyond its exit stretches.
std::vector<bool> beyond_skin_ends(const std::vector<Eigen::Vector3d>& line, const ExitStretches& exits);

/// `fibers`: each fiber's centre line as a dense polyline (m); groove `radius`, laid muscles of
/// `muscle_radius` resting on the grooves' bottoms. Within a fiber's `exits` (one per fiber), where it
/// leaves the body by design, neither is measured. `voxel`: the
/// groove body's, which blurs its walls by about one.
SiliconeThickness silicone_thickness(const SurfaceMesh& groove_body, const SurfaceMesh& body,
                                     const std::vector<std::vector<Eigen::Vector3d>>& fibers, double radius,
                                     double muscle_radius, const Eigen::Vector3d& pull, double voxel,
                                     const std::vector<ExitStretches>& exits);

} // namespace fibermold
