#pragma once
// What the molds' grids would hold for a body, estimated before any is made: the level set's
// narrow band over the skin and the grooves (its voxel count sets the carving's time and memory,
// and the meshed cavity's triangles the booleans'), and the fill simulation's dense grid. An
// absurd combination (a 0.01 mm voxel on a 300 mm body, a 100 mm groove) is refused at once
// rather than carved for hours.

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "mesh/surface_mesh.hpp"

namespace fibermold {

struct GridEstimate {
  double band_voxels = 0; ///< the level set's narrow band: 6 voxels across the skin and the grooves' walls
  double fill_voxels = 0; ///< the fill simulation's grid over the body's box
};

/// Estimates for `body` carved at `voxel` (m) with grooves of `radius` (m) along the polylines `fibers`.
GridEstimate estimate_grids(const SurfaceMesh& body, double voxel, double radius,
                            const std::vector<std::vector<Eigen::Vector3d>>& fibers);

/// 25× the twisting bar's band (1.9 million voxels at 0.2 mm): minutes of carving, a few GB.
constexpr double kMaxBandVoxels = 5e7;
/// Four bytes a voxel: 2 GB.
constexpr double kMaxFillVoxels = 5e8;

/// Why the grids are too big for a run, with what to change; empty when they are not.
std::optional<std::string> grid_budget_problem(const GridEstimate& estimate, double voxel);

} // namespace fibermold
