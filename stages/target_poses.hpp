#pragma once
// Poses: the rigid motion a `kind = "pose"` target asks of its regions, and the pose that every
// target's regions and the tracking curves' ends reach in a deformation (docs/targets.md), so that
// a user sizes a target by its angle and translation instead of its largest displacement.

#include <array>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "design/design.hpp"
#include "export/behaviour_summary.hpp" // kSensitivityChange, kPoseVariations
#include "mesh/tet_mesh.hpp"
#include "sim/rigid_motion.hpp"
#include "sim/simulation.hpp"

namespace fibermold {

/// One region of a pose target on the mesh: its nodes and the motion asked of them.
struct PosedRegion {
  std::string key; ///< e.g. "[target.curl].pose[1]"
  std::vector<int> nodes;
  Eigen::Vector3d axis;  ///< unit
  double angle = 0;      ///< rad
  Eigen::Vector3d about; ///< m
  Eigen::Vector3d translation;
  /// The motion a fraction s of the way: turned by s·angle about the same line, moved by s·translation.
  RigidMotion at(double s) const { return rotation_about(axis, s * angle, about, s * translation); }
};

/// The regions of a pose target. InputError for a region that selects no node, or that shares
/// nodes with a [[fixed]] region or another pose (a node cannot be held in two places).
std::vector<PosedRegion> target_poses(const Design& d, const Target& t, const TetMesh& mesh);

/// Where a region, a point or a tracking curve's end went: its displacement (of the centroid, m)
/// and its rotation (fitted to the region's nodes, or the material's at a point).
struct ReachedPose {
  std::string place;                              ///< "load[1]", "pose[1]", "centreline, last point"
  int nodes = 0;                                  ///< 0 for a point
  Eigen::Vector3d rest = Eigen::Vector3d::Zero(); ///< the point, or the nodes' centroid, m
  Eigen::Vector3d displacement = Eigen::Vector3d::Zero();
  RigidMotion motion;
  const PosedRegion* asked = nullptr; ///< for a pose target's region: what it was asked
};

/// The poses reached in deformation x of `sim` by target t's load or pose regions and by both
/// ends of every tracking curve.
std::vector<ReachedPose> reached_poses(const Design& d, const Target& t, const Simulation& sim,
                                       const Eigen::VectorXd& x, const std::vector<PosedRegion>& asked);

/// A reached pose for a report: translation in mm, rotation in degrees and its axis; for a pose
/// region also the angle asked and the angle reached about the asked axis.
nlohmann::ordered_json pose_report(const ReachedPose& p);

/// pose_report(p) and, under "sensitivity", where p went under each of kPoseVariations (`varied`, in
/// that order): its rotation (deg), its displacement's length (mm) and, for a pose region, its
/// rotation about the asked axis (deg), each {variation: value}.
nlohmann::ordered_json pose_report(const ReachedPose& p, const std::array<ReachedPose, 4>& varied);

} // namespace fibermold
