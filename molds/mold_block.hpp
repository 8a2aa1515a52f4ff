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
#include "molds/part_label.hpp"
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
  std::vector<PlacedLabel> labels;     ///< engraved, in the body's frame: the part's own label, then "IN" per sprue
  std::vector<std::string> unlabelled; ///< why a label was left out, one line each (no room on any face)
};

/// What make_mold engraves on its parts (part_label.hpp): on each half "<DESIGN> S<shot> <LOWER|UPPER>"
/// (shorter forms where that does not fit) on its longest side face that takes it, else on its outer
/// end face; "IN" beside each sprue's mouth on the end face it opens through.
struct PartLabels {
  std::string design; ///< the design's name, cut in capitals; empty: the shot and half alone
  LabelStyle style;
};

/// The texts tried for a part's label, longest first, in capitals: "GRIPPER S1 LOWER", "GRIPPER S1L", "S1 LOWER",
/// "S1L".
std::vector<std::string> part_label_texts(const std::string& design, const std::string& shot, bool lower);

/// Two channels (indices into make_mold's `channels`), as laid parallel to the parting plane, whose
/// walls come closer than min_wall: the mold between them (m; negative where they overlap).
struct CloseChannels {
  int a = 0, b = 0;
  double wall = 0;
};

struct Mold {
  std::vector<MoldPart> parts;
  std::vector<CloseChannels> close_channels; ///< pairs of channels closer than min_wall, as laid
  std::vector<Eigen::Vector3d> sprues;       ///< where each sprue meets the cavity
  std::vector<Eigen::Vector3d> vents;        ///< where each vent meets the cavity
  std::vector<Eigen::Vector3d> keys; ///< key centres on the parting plane; sites on a channel's way are left out
  std::vector<Eigen::Vector3d>
      screws; ///< screw hole axes' points on the parting plane (fewer than asked when channels and keys leave no room)
  double label_seconds = 0; ///< s, placing and cutting the parts' labels
};

/// The margin make_mold grows a cavity's bounding box by, in the frame where the pull is +z: across the pull the
/// wall, or the room the keys and screw holes take in the rim, whichever is more; along it the wall.
Eigen::Vector3d block_margin(const MoldBlockOptions& options);

/// The least size of the larger half that make_mold cuts around `cavity` opened along `pull`, as the parts are
/// checked (their bounding box in the design's frame): the box of the block's width and depth and half its height
/// in the pull's frame (the halves share the height however the parting plane divides it), turned back. A half of
/// this size that fits no printer orientation will not fit as made either.
Eigen::Vector3d least_half_size(const SurfaceMesh& cavity, const Eigen::Vector3d& pull,
                                const MoldBlockOptions& options);

/// The sprues and vents are `ports`, or without them the cavity's own (cavity_ports: a sprue from
/// below at the lowest flat spot, `options.vents` vents along the top). Throws std::runtime_error
/// when a boolean fails or the cavity has no spot for its sprue.
/// With `labels`, each part is engraved as PartLabels says, where there is room; a label that fits
/// nowhere, or whose cut fails, is left out and said so in the part's `unlabelled`.
Mold make_mold(const SurfaceMesh& cavity, const Parting& parting, const std::vector<Channel>& channels,
               const MoldBlockOptions& options, const std::string& shot, const Ports* ports = nullptr,
               const PartLabels* labels = nullptr);

} // namespace fibermold
