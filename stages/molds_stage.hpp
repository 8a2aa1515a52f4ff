#pragma once
// The molds stage (paper section VII, Fig. 7): the two shots of the casting.
//   shot 1: the body with an open groove per muscle (level set), in a two-part mold;
//   shot 2: the full body, the overmold that closes the grooves over the laid-in muscles, with
//           channels where the fibers leave the body for their ends and supply tubes.
// Fiber routes come from collide/fibers.json (the [[fiber]] routes when [optimize] enabled =
// false, given their clearance by collide all the same). Every part is checked (part_checks.hpp);
// any failed check fails the stage and nothing is written. Outputs: molds/<shot>-lower.stl, <shot>-upper.stl (mm, in
// the body's frame), groove-body.stl, report.json.

#include "make/stage.hpp"
#include "mesh/surface_distance.hpp"
#include "mesh/surface_mesh.hpp"
#include "molds/silicone_thickness.hpp"
#include "optimize/routing_problem.hpp"

namespace fibermold {

/// Refuses (InputError on [mold].voxel) a voxel too fine for the body and its grooves along the
/// polylines `fibers` (molds/grid_budget.hpp), before any carving; `check` asks it too.
void require_mold_grids(const Design& d, const SurfaceMesh& body,
                        const std::vector<std::vector<Eigen::Vector3d>>& fibers);
/// Refuses (InputError on [export].printer_volume) a body whose molds' larger half, at its least (the block
/// around the body grown by the shrink, the wall and the rim, half its height), fits the printer in no
/// orientation: found before the optimizer runs, not after the molds are carved; `check` asks it too.
void require_molds_fit_printer(const Design& d, const SurfaceMesh& body);
/// InputError at the fiber when a route's groove does not fit inside the body (molds' rule:
/// groove_problem) off its `exits` (one per route); the routes' lines as the molds sample them.
std::vector<std::vector<Eigen::Vector3d>> require_grooves_fit(const Design& d, const SurfaceDistance& skin,
                                                              const std::vector<Route>& routes,
                                                              const std::vector<ExitStretches>& exits);

class MoldsStage final : public Stage {
public:
  std::string name() const override { return "molds"; }
  std::vector<std::string> upstream() const override { return {"mesh", "collide"}; }
  std::vector<std::string> design_keys() const override
  {
    // the design's name: engraved on the parts; fiber, muscle, target, collide's resolution: the routes the optimizer
    // started from, which set where its skin barrier held a fiber (exit_stretches)
    return {"design.name",
            "design.units",
            "material.density",
            "muscle",
            "fiber",
            "target",
            "collide.clearance",
            "collide.smoothness",
            "collide.samples_per_mm",
            "mold",
            "export.min_wall",
            "export.printer_volume"};
  }
  /// 2: sprues and vents from the fill simulation, its report, the silicone's thickness; 3: a remeshed body molded as
  /// given; 4: the groove rule shared (skin_distance.hpp), 10 µm of placement tolerance; 5: routes under [muscle]
  /// min_bend_radius refused; 6: the stretches at the ends on the skin left out where the optimizer's skin barrier left
  /// them out (exit_stretches), not 2 × (diameter + clearance); 7: no sprue or vent within min_wall of a cavity wall
  /// rising beside it; 8: with an "auto" parting plane, the pull reversed when it leaves a half of shot 1 a plate; 9:
  /// the sprues countersunk; 10: each part engraved with the design's name, shot and half, "IN" beside each sprue
  /// (report: each part's labels and labels_left_out); 11: a route's tightest bend the tightest of each span's peaks;
  /// 12: label heights max − k·step (report: 7 mm, not 6.999999999999999), every mesh in a canonical order (the
  /// same parts byte for byte from run to run); 13: each shot's thin deep ribs (report: thin_ribs; warned without
  /// draft); 14: thin ribs found by a disk's closing, a valley's wall not a rib of its own; 15: a silicone
  /// thickness nothing measured has no place in the report (was (0, 0, 0)); 16: each part's thinnest wall's place
  /// (report: min_wall_at_mm); 17: no vent or sprue whose cut leaves a wall under min_wall to the cavity beside it;
  /// 18: an "auto" plane in the middle of the widest range of heights within 0.05 mm² of the least undercut
  int version() const override { return 18; }
  void run(StageContext& ctx) const override;
};

} // namespace fibermold
