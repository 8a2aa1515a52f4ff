#pragma once
// One shot's fill, simulated as the silicone rises in the filling stance (pull up, README.txt):
// it enters through the sprues, runs to the lowest point it can reach and rises level by level
// (voxel layers along pull). Air escapes through the vents; air that the rising level closes off
// from every vent stays as a pocket. Voxels are 26-connected, liquid and air alike: a crevice
// thinner than a voxel (beside a muscle's line of contact with its groove) is sampled as voxels
// touching at edges or corners, and is not cut off by the sampling. Computed exactly on the voxels by one sweep
// from the top down with a union-find (a merge tree of the air above each level): where a part of
// the air above a level without a vent joins one with a vent, the liquid reaching that level seals
// it, with the volume it has above the level. A part no sprue reaches is not filled at all.

#include <vector>

#include <Eigen/Core>

#include "molds/voxel_region.hpp"

namespace fibermold {

/// A sprue or vent: a round hole drilled through the mold along pull to its mouth on the cavity.
/// It takes in the fill voxels it meets first from outside in each column of its disc, to its dip
/// past the mouth: none where it meets solid (a vent over cured silicone).
struct Port {
  Eigen::Vector3d mouth; ///< m, body frame: where the hole meets the cavity
  double diameter = 0;   ///< m
  bool upward = true;    ///< leaves along +pull (vents, a sprue from above) or −pull (a sprue from below)
  /// m: how far past its mouth the mold cuts the hole, so that its whole disc lies in the cavity
  /// (a sloping skin under it) and the booleans meet no tangent faces; 0: dip()
  double depth = 0;

  double dip() const { return depth > 0 ? depth : diameter / 2 < 0.5e-3 ? diameter / 2 : 0.5e-3; }
};

struct AirPocket {
  double volume = 0;                            ///< m³
  Eigen::Vector3d at = Eigen::Vector3d::Zero(); ///< m: a pocket's highest point, an unfilled part's lowest
  bool ventable =
      true; ///< a pocket's top has mold straight above it (not cured silicone or a muscle): a vent can reach it
  bool thin = false; ///< no voxel of the pocket has all six face neighbours in the region
};

struct FillResult {
  double fill_volume = 0;             ///< m³: the region the shot must fill
  double reachable_volume = 0;        ///< m³: connected to a sprue
  double trapped_volume = 0;          ///< m³: air the rising silicone closes off from every vent, crevices left out
  std::vector<AirPocket> pockets;     ///< trapped air, largest first, crevices left out
  std::vector<AirPocket> unreachable; ///< parts no sprue reaches, largest first, crevices left out
  /// Air that a pocket holds as a part of its own, of 1 mm³ or more, largest first: where two parts
  /// without a vent join, the smaller, sealed off once the other has a vent (not counted as trapped)
  std::vector<AirPocket> nested;
  /// m³: parts no sprue reaches that are crevices thinner than two voxels (no voxel of theirs has
  /// all six face neighbours in the region), such as the wedge along a muscle's line of contact
  /// with its groove's bottom, which the sampling cuts off from the rest
  double crevice_volume = 0;
  /// m³: air in such crevices under cured silicone or a muscle (pockets no thicker than two voxels
  /// whose top no vent can reach): sampled as closed off, though the gap goes on below a voxel
  double crevice_air_volume = 0;
  /// m³: shot 1's air at a groove's mouth (a thin pocket whose top lies beside shot 2's fill
  /// region, as in the wedge of cast between a groove's wall and a sloping skin): what it leaves
  /// empty, shot 2's silicone fills (plan_fill)
  double overmolded_air_volume = 0;
  std::vector<bool> sprue_open; ///< the sprue opens onto the region
  std::vector<bool> vent_open;  ///< the vent opens onto a part of the region that a sprue reaches
};

FillResult simulate_fill(const VoxelRegion& region, const std::vector<Port>& sprues, const std::vector<Port>& vents);

} // namespace fibermold
