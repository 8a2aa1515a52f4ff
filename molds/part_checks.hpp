#pragma once
// The checks every printed part must pass before it is exported: a closed, manifold, consistently
// and outward oriented surface without self-intersections, in one piece, no wall thinner than the
// printer's minimum (rays cast inward from each face, part_checks.cpp), and a fit in the printer's build volume
// in one of the 6 axis-aligned orientations.

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "mesh/surface_mesh.hpp"

namespace fibermold {

struct PartCheck {
  std::vector<std::string> problems;              ///< empty: the part passed
  double volume = 0;                              ///< m³
  Eigen::Vector3d size = Eigen::Vector3d::Zero(); ///< bounding box, m
  double min_thickness = 0; ///< m, the thinnest wall found (a cone median where a single ray saw < min_wall)
  Eigen::Vector3d min_thickness_at = Eigen::Vector3d::Zero(); ///< m, where, in the part's frame as checked
  bool thin_wall = false;                                     ///< min_thickness is under min_wall: one of the problems
  Eigen::Vector3i orientation{0, 1, 2};                       ///< part axes along the printer's x, y, z that fit
  bool fits = false;

  bool ok() const { return problems.empty(); }
};

PartCheck check_part(const SurfaceMesh& part, double min_wall, const Eigen::Vector3d& printer_volume);

/// Which part axis goes along the printer's x, y, z for a box of `size` to fit `printer_volume`, of the 6
/// axis-aligned orientations the one of lowest build height; none when none fits.
std::optional<Eigen::Vector3i> printer_orientation(const Eigen::Vector3d& size, const Eigen::Vector3d& printer_volume);

} // namespace fibermold
