#pragma once
// Closed, outward-oriented triangle meshes of the simple solids a mold is built from: boxes for
// blocks, cylinders for sprues, vents, channels and screw holes, cones and hemispheres for keys.

#include <Eigen/Core>

#include "mesh/surface_mesh.hpp"

namespace fibermold {

SurfaceMesh box_solid(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi);
/// A cylinder from a to b of the given radius, `segments` around (a polygon inscribed in the circle).
SurfaceMesh cylinder_solid(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double radius, int segments = 32);
/// A truncated cone from a (radius ra) to b (radius rb > 0).
SurfaceMesh cone_solid(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double ra, double rb, int segments = 32);
/// The half ball of `radius` centred at c on the side of `axis`, closed by its flat disc.
SurfaceMesh hemisphere_solid(const Eigen::Vector3d& c, const Eigen::Vector3d& axis, double radius, int segments = 32);

} // namespace fibermold
