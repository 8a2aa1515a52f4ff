#pragma once
// The optimize stage (paper sections IV-C and V): co-optimizes the fibers' routes and each
// target's pressures so that the actuated body matches every target along the tracking curves.
// Outputs: optimize/fibers.json, history.csv (one row per BFGS iteration), deformed-<target>.vtu,
// report.json (per target RMSE and max error on the tracking curves and the surface, pressures,
// timings). With [optimize] enabled = false it passes the [[fiber]] routes through unchanged.
// Ctrl-C stops it and keeps the best design so far in <build>/optimize.interrupted/.

#include "make/stage.hpp"
#include "mesh/surface_distance.hpp"
#include "stages/routing_keys.hpp"

namespace fibermold {

/// What the optimize stage refuses as bad input before it simulates anything: no fiber, target or
/// tracking curve; a sequential strategy with as many fibers as targets not given; a fiber or a
/// tracking curve that leaves the body (`skin`: the body's surface). Nothing when [optimize] enabled = false. `check`
/// asks it too, so that a design check passes is not refused by make.
void require_optimizable(const Design& d, const SurfaceDistance& skin);

class OptimizeStage final : public Stage {
public:
  std::string name() const override { return "optimize"; }
  std::vector<std::string> upstream() const override { return {"mesh", "targets"}; }
  std::vector<std::string> design_keys() const override
  {
    // the surface and [mesh]: [optimize] refine meshes the body again; [collide]: the clearance it keeps
    // (clearance_barrier.hpp) and the moves apart before optimizing (optimization_start)
    return routing_design_keys(
        {"design.surface", "mesh", "collide.clearance", "collide.samples_per_mm", "collide.smoothness"});
  }
  /// 2: fibers moved apart before optimizing, kept apart throughout; 3: termination, warnings and reach in the
  /// report; 4: reached poses; 5: the bend radius barrier, bends in the report; 6: the bend barrier samples each
  /// span's tightest point, [optimize] method; 7: history.csv predicted_decrease, report.json refused,
  /// Levenberg-Marquardt's secant term, method hybrid (the default); 8: the start's skin tested where the skin
  /// barrier holds it; 9: Levenberg-Marquardt's ray model, [optimize] starts (report.json starts, history.csv start);
  /// 10: each span's tightest point the tightest of its peaks, Levenberg-Marquardt's choice of model over recent steps;
  /// 11: Levenberg-Marquardt's model always B + S, S learning only what B leaves out of the simulation's part;
  /// 12: exact Newton steps near the tolerance where pairs are lumped, closed-form Hessian products (report.json
  /// newton.hessian_products); 13: the muscles' Hessian products exact, Levenberg-Marquardt's ray model taking
  /// out the barriers' expansion as its model holds it, a route at its smallest bend radius named in the warnings;
  /// 14: Levenberg-Marquardt stalls only where its model predicted too much at every iteration of the window;
  /// 15: the model's clearance-barrier Hessian from each fiber's own pairs; 16: Levenberg-Marquardt forgets its
  /// secant term where B + S alone claims convergence; 17: a stop on rejected steps gives the last step's length, not
  /// the damping (which doubling had taken to 1e68); 18: the skin barrier's dip term between samples; 19: the first
  /// guess is kept where it matches the targets better (report.json first_guess.distance); 20: the turn's error where
  /// a curve's orientation is tracked (orientation_rms_deg, orientation_max_deg), first_guess's surface errors;
  /// 21: the exit ramp (a fiber's exit stretch held at d_min · s / (2(d_min + w)), skin_barrier.hpp); 22: the ramp
  /// measured on the route as it is (ρ, the distance from the end, not the starting arc); 23: a pose's region
  /// short of its turn (under 90 % of its angle) warned, with the muscles' pressures; the skin barrier's weight 0.1
  /// by default (was 1)
  int version() const override { return 24; }
  void run(StageContext& ctx) const override;
};

} // namespace fibermold
