#pragma once
// Where a shot's sprues and vents go. A shot starts from the holes its cavity's shape suggests (a
// sprue from below at the lowest flat spot, vents spread along the top: cavity_ports) or from none;
// the fill simulation then adds a sprue for every part of the fill region that no sprue reaches
// (from below at its lowest point, or, where cured silicone lies below it as in shot 2, from above
// straight over its lowest point) and a vent at the top of every pocket of air the rising silicone
// would close off, until the trapped air is within the tolerance (plan_fill).

#include <string>
#include <vector>

#include <Eigen/Core>

#include "mesh/surface_mesh.hpp"
#include "molds/fill_simulation.hpp"
#include "molds/voxel_region.hpp"

namespace fibermold {

struct Ports {
  std::vector<Port> sprues, vents;
};

/// The trapped air a shot may keep: a cubic millimetre (voxel facets of a curved top give pockets
/// of a few voxels that no vent is needed for).
constexpr double kTrappedAirTolerance = 1e-9; // m³
constexpr int kMaxVents = 16, kMaxSprues = 8;

/// The sprue at the cavity's lowest flat spot, from below (the whole hole, grown by `margin`, lands
/// on the bottom within 0.5 mm of its lowest point), and up to `vents` vents spread along its top.
/// Throws std::runtime_error, naming `shot`, when the bottom has no spot for the sprue.
Ports cavity_ports(const SurfaceMesh& cavity, const Eigen::Vector3d& pull, double sprue_diameter, int vents,
                   double vent_diameter, double margin, const std::string& shot);

struct FillPlan {
  Ports ports;
  FillResult fill;               ///< of the ports as placed
  int simulations = 0;           ///< fill simulations run to place them
  double simulation_seconds = 0; ///< their time, apart from the search for the holes' sites
};

/// `ports` completed by the fill simulation of `region`, whose mold is made around `cavity`:
/// sprues from above when `sprue_from_above`, until what no sprue reaches and the trapped air are
/// each within `tolerance` (m³). A hole it adds meets the cavity within 3 mm of the place it is
/// wanted (6 or 12 mm where nothing nearer takes it; holes keep 1 mm apart; a vent not above the
/// top of its pocket),
/// where it opens on the fill region and the skin under its rim slopes by at
/// most 35° or drops away by 2 mm or more (a steeper skin leaves a knife edge of mold beside the
/// hole), and where the skin does not rise beside it within `min_wall` of its wall; it is cut
/// 0.5 mm past the deepest of that skin under its rim.
///
/// With `overmold` (shot 2's fill region, for shot 1), a thin pocket whose top lies within two
/// voxels of it sits at a groove's mouth (the wedge of cast between a groove's wall and a sloping
/// skin): shot 2 fills what it leaves, so it needs no vent and is not counted as trapped.
FillPlan plan_fill(const VoxelRegion& region, const SurfaceMesh& cavity, Ports ports, double sprue_diameter,
                   double vent_diameter, double min_wall, bool sprue_from_above, const VoxelRegion* overmold = nullptr,
                   double tolerance = kTrappedAirTolerance);

} // namespace fibermold
