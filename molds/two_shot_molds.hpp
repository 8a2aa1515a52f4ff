#pragma once
// Two-shot molds (paper section VII, Fig. 7): from the body and its fibers' centre lines to the
// mold parts of both shots, checked.
//   shot 1: the body with an open groove per muscle (level set), in a two-part mold filled from below;
//   shot 2: the full body, the overmold that closes the grooves over the laid-in muscles and the
//           cured shot 1, filled from above, with channels where the fibers leave the body.
// Shrink compensation scales the cavities up about the body's centre; a draft grows them away from
// the parting plane (draft.hpp); the fill simulation places sprues and vents (ports.hpp); every
// part is checked (part_checks.hpp), and the cast silicone's thinnest places are measured
// (silicone_thickness.hpp). Nothing is written here: the molds stage writes what this returns.

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/progress.hpp"
#include "mesh/surface_distance.hpp"
#include "mesh/surface_mesh.hpp"
#include "molds/groove.hpp"
#include "molds/mold_block.hpp"
#include "molds/mold_options.hpp"
#include "molds/part_checks.hpp"
#include "molds/parting.hpp"
#include "molds/ports.hpp"
#include "molds/silicone_thickness.hpp"
#include "molds/thin_ribs.hpp"

namespace fibermold {

/// A fiber as the molds see it.
struct MoldFiber {
  std::string name;                  ///< the [[fiber]]'s, for messages
  std::vector<Eigen::Vector3d> line; ///< the centre line, sampled along the spline
  Eigen::Vector3d start, end;        ///< the spline's end points
  Eigen::Vector3d start_tangent;     ///< along the fiber at its first point
  Eigen::Vector3d end_tangent;       ///< along the fiber at its last point
  double length = 0;                 ///< m, of the spline
};

/// What the molds are made for: the body and its muscles.
struct MoldJob {
  std::string name; ///< the design's, engraved on each part with its shot and half (mold_block.hpp's PartLabels)
  SurfaceMesh body; ///< the body's skin, m
  std::vector<MoldFiber> fibers;
  double muscle_diameter = 0; ///< m
  /// Per fiber, the stretches at its ends on the skin that the thickness checks leave out (the
  /// optimizer's skin barrier's; the fiber leaves the body there by design).
  std::vector<ExitStretches> exits;
  double min_wall = 1e-3;                           ///< m, the printer's thinnest reliable wall
  Eigen::Vector3d printer_volume{0.25, 0.21, 0.21}; ///< m
};

/// m: how far short of a distance the molds ask of a fiber (from the skin, of silicone beside its
/// groove) a fiber may come and pass: the stages that place fibers (optimize, collide) sample
/// them differently and keep them at the distance within a micrometre.
inline constexpr double kPlacementTolerance = 10e-6;

/// The radius of a fiber's groove: the muscle's and the clearance around it for laying it in.
double groove_radius(double muscle_diameter, const MoldOptions& options);

/// The fiber sampled for the molds: about every `step` along its spline, no coarser than 0.5 mm
/// nor than two voxels.
double mold_line_step(const MoldOptions& options);

/// Why a fiber's groove cannot be cast, or nothing: the fiber must stay in the body, and its centre
/// line `need` (m) from the skin (other than below the skin above it, where the groove opens), so
/// that the groove neither breaks through the skin nor leaves a skin too thin to cast; `terms`
/// says what `need` is made of. On its `exits`, where the fiber leaves the body by design, it is
/// exempt. A fiber short of `need` by less than kPlacementTolerance passes.
std::optional<std::string> groove_problem(const std::vector<Eigen::Vector3d>& line, const SurfaceDistance& skin,
                                          double need, const std::string& terms, const Eigen::Vector3d& pull,
                                          const ExitStretches& exits);

/// One shot's mold.
struct ShotMold {
  std::string name;           ///< shot1 | shot2
  FillPlan plan;              ///< sprues, vents and the fill simulation, on the nominal body (scaled() maps it)
  double fill_voxel = 0;      ///< m, of the fill simulation's grid
  Parting parting;            ///< in the scaled cavity
  double cavity_volume = 0;   ///< m³, scaled
  double upright_share = 0;   ///< of the upper half's contact within 3° of the pull
  double silicone_volume = 0; ///< m³ the shot pours
  std::size_t sprues = 0, vents = 0, keys = 0, screw_holes = 0;
  std::vector<ThinRib> thin_ribs; ///< thin deep ribs of its halves (thin_ribs.hpp), deepest first
};

struct CheckedPart {
  std::string shot;
  MoldPart part;
  PartCheck check;
};

struct TwoShotMolds {
  std::vector<ShotMold> shots;                     ///< shot1, shot2
  std::vector<CheckedPart> parts;                  ///< every part of both shots, checked
  GrooveBody groove;                               ///< shot 1's cast: the body with its grooves (nominal size)
  double groove_radius = 0;                        ///< m
  double draft_offset = 0;                         ///< m, the most a draft grew a cavity (0: no draft)
  Eigen::Vector3d pull = Eigen::Vector3d::UnitZ(); ///< unit: the pull the molds were made for
  SiliconeThickness thickness;
  /// What keeps the molds from casting, one line each naming the shot and where; empty: they cast.
  std::vector<std::string> failures;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero(); ///< the shrink scaling's centre
  double grow = 1;                                  ///< the shrink scaling's factor

  /// A point of the nominal body in the scaled cavities.
  Eigen::Vector3d scaled(const Eigen::Vector3d& p) const { return centre + (p - centre) * grow; }
};

/// Where the recipe's findings go as it works (the stage's log).
struct MoldLog {
  std::function<void(const std::string&)> info = [](const std::string&) {};
  std::function<void(const std::string&)> warn = [](const std::string&) {};
};

/// Both shots' molds for `job`. Throws Interrupted when `progress` says so.
TwoShotMolds two_shot_molds(const MoldJob& job, const MoldOptions& options, Progress& progress,
                            const MoldLog& log = {});

} // namespace fibermold
