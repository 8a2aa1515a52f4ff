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

struct SiliconeThickness {
  /// m: the thinnest shot-1 silicone between a groove's walls (more than its radius below its
  /// mouth) and the skin; below 2 mm, else +∞
  double groove_web = HUGE_VAL;
  Eigen::Vector3d groove_web_at = Eigen::Vector3d::Zero();
  double overmold = HUGE_VAL;    ///< m: the thinnest shot-2 silicone over a muscle
  Eigen::Vector3d overmold_at = Eigen::Vector3d::Zero();
};

/// Per point of a fiber's polyline: whether it lies beyond the stretch, `exempt` (m) long along
/// the fiber, at an end that lies on the skin (within exempt / 2 of it), where the fiber leaves the
/// body by design. The molds' route check and the silicone's thickness leave that stretch out.
std::vector<bool> beyond_skin_ends(const std::vector<Eigen::Vector3d>& line, const SurfaceDistance& skin, double exempt);

/// `fibers`: each fiber's centre line as a dense polyline (m); groove `radius`, laid muscles of
/// `muscle_radius` resting on the grooves' bottoms. Within `exempt` (m, along the fiber) of an end on
/// the skin, where a fiber leaves the body by design, the overmold is not measured. `voxel`: the
/// groove body's, which blurs its walls by about one.
SiliconeThickness silicone_thickness(const SurfaceMesh& groove_body, const SurfaceMesh& body,
                                     const std::vector<std::vector<Eigen::Vector3d>>& fibers, double radius, double muscle_radius,
                                     const Eigen::Vector3d& pull, double voxel, double exempt);

} // namespace fibermold
