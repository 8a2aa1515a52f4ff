#pragma once
// Placing a part for printing: on its largest planar face (the face-groups of equal normal and
// plane offset, by area), turned about the vertical to fit the printer's bed, moved to the origin.

#include <Eigen/Core>

#include "mesh/surface_mesh.hpp"

namespace fibermold {

struct Placement {
  SurfaceMesh part;     ///< rigidly moved: min corner at the origin, z up
  Eigen::Vector3d size; ///< m
  double flat_area = 0; ///< m², of the face it stands on
  bool fits = false;    ///< within the printer's volume
  /// The rigid motion from the body's frame to the printed pose: printed = rotation · p + translation.
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero(); ///< m
};

Placement lay_flat(const SurfaceMesh& part, const Eigen::Vector3d& printer_volume);

} // namespace fibermold
