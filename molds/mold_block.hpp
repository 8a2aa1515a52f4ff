#pragma once
// A two-part mold around a cavity (paper Fig. 7): the cavity's bounding box, grown by the wall
// (and wide enough in the parting plane for the keys), minus the cavity; injection sprues and
// vents along pull (ports.hpp), channels for the fibers' ends and supply tubes, split by the
// parting plane into a lower and an upper part with registration keys: pins on the lower part, matching sockets (grown
// by the fit clearance) in the upper one. Built in a frame where the pull direction is +z, returned in the body's
// frame.

#include <string>
#include <vector>

#include <Eigen/Core>

#include "mesh/surface_mesh.hpp"
#include "molds/mold_options.hpp"
#include "molds/parting.hpp"
#include "molds/ports.hpp"

namespace fibermold {

/// A straight channel, e.g. where a fiber leaves the body: from `start` (inside the body) along
/// `direction` out through the mold wall; laid parallel to the parting plane, and onto it when it
/// starts within its radius + min_wall of it. It is `diameter` wide for `socket` from its start (the
/// muscle's end and its supply tube sit there, and the silicone closes around them), then
/// `through_diameter` wide out through the wall (the tube leaves the mold; 0: `diameter` all the way).
struct Channel {
  Eigen::Vector3d start, direction;
  double diameter;
  double socket = 0;           ///< m
  double through_diameter = 0; ///< m
};

struct MoldPart {
  std::string name; ///< "<shot>-lower", "<shot>-upper"
  SurfaceMesh mesh;
};

struct Mold {
  std::vector<MoldPart> parts;
  std::vector<Eigen::Vector3d> sprues; ///< where each sprue meets the cavity
  std::vector<Eigen::Vector3d> vents;  ///< where each vent meets the cavity
  std::vector<Eigen::Vector3d> keys;   ///< key centres on the parting plane; sites on a channel's way are left out
  std::vector<Eigen::Vector3d>
      screws; ///< screw hole axes' points on the parting plane (fewer than asked when channels and keys leave no room)
};

/// The sprues and vents are `ports`, or without them the cavity's own (cavity_ports: a sprue from
/// below at the lowest flat spot, `options.vents` vents along the top). Throws std::runtime_error
/// when a boolean fails or the cavity has no spot for its sprue.
Mold make_mold(const SurfaceMesh& cavity, const Parting& parting, const std::vector<Channel>& channels,
               const MoldBlockOptions& options, const std::string& shot, const Ports* ports = nullptr);

} // namespace fibermold
