#pragma once
// The design file's [mold] section (docs/design-file.md, "[mold]"), in SI: each default written
// here once; the design file reads into these structs.

#include <optional>
#include <string>

#include <Eigen/Core>

#include "core/names.hpp"

namespace fibermold {

/// The registration keys' shape: pins on the lower half, sockets in the upper.
enum class KeyShape { cone, hemisphere };
inline constexpr std::array<Named<KeyShape>, 2> kKeyShapeNames{
    {{KeyShape::cone, "cone"}, {KeyShape::hemisphere, "hemisphere"}}};
inline std::string_view choice_name(KeyShape k) { return name_in(kKeyShapeNames, k); }

/// The mold block around one shot's cavity (mold_block.hpp).
struct MoldBlockOptions {
  double wall = 4e-3, min_wall = 1e-3;
  int keys = 4; ///< 0 to 8: block corners first, then edge midpoints
  KeyShape key_shape = KeyShape::cone;
  double key_diameter = 6e-3, key_clearance = 0.2e-3;
  double sprue_diameter = 4e-3;
  int vents = 2;
  double vent_diameter = 1.5e-3;
  int screw_holes = 0; ///< 0 to 16, through both halves along pull, in the rim around the cavity
  double screw_diameter = 3.4e-3;
};

struct PartingPlane {
  Eigen::Vector3d point;  ///< m
  Eigen::Vector3d normal; ///< unit
};

/// Both shots' molds (two_shot_molds.hpp).
struct MoldOptions {
  MoldBlockOptions block;              ///< wall, keys, sprue, vents, screws; its min_wall is [export]'s
  double voxel = 0.2e-3;               ///< m
  Eigen::Vector3d pull{0, 0, 1};       ///< unit
  std::optional<PartingPlane> parting; ///< absent: "auto"
  double groove_clearance = 0.3e-3;    ///< m
  double min_silicone = 0.5e-3;        ///< m, the thinnest cast silicone at a groove and over a muscle
  double end_channel_length = 5e-3;    ///< m
  double end_channel_diameter = 4e-3;  ///< m
  double draft_deg = 0;                ///< degrees
  double shrink = 0;                   ///< linear shrink of the silicone, fraction
  bool labels = true;                  ///< engrave each part's name and "IN" beside its sprues (part_label.hpp)

  /// Shrink compensation: how much the cavities are scaled up, so that the cured silicone shrinks to size.
  double shrink_growth() const { return shrink > 0 ? 1 / (1 - shrink) : 1.0; }
};

} // namespace fibermold
