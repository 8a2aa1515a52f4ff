#pragma once
// The collide stage, between optimize and molds: fibers that come closer to each other or to the
// skin than [collide] clearance are moved apart by the smallest smooth change of their routes
// (optimize/collision_resolution.hpp; the paper did this by hand, sections V-B and VIII-F), and
// every target is simulated again with the resolved routing and its pressures, to show the robot
// still does its job; with [collide] reoptimize = true the optimizer then runs again from the
// resolved routing with the clearance between fibers as a barrier. Outputs: collide/fibers.json (optimize's schema),
// report.json (collisions, smallest clearance before and after, how far each control point moved, per-target errors
// before and after), deformed-<target>.vtu. A clear routing passes through bit for bit; a clearance that cannot be had
// fails the stage, naming the fibers and the place.

#include "make/stage.hpp"
#include "stages/routing_keys.hpp"

namespace fibermold {

class CollideStage final : public Stage {
public:
  std::string name() const override { return "collide"; }
  std::vector<std::string> upstream() const override { return {"mesh", "targets", "optimize"}; }
  std::vector<std::string> design_keys() const override { return routing_design_keys({"collide"}); }
  /// 2: writes deformed-<target>.json for the report; 3: no null in report.json; 4: bends in the report, routes
  /// under min_bend_radius refused; 5: the bend barrier samples each span's tightest point, min_bend_radius_mm in the
  /// report; 6: Levenberg-Marquardt's secant term, method hybrid (the default); 7: the skin tested where the
  /// optimizer's skin barrier held it (SkinBarrier::held); 8: each target's poses reached (where its regions and the
  /// tracking curves' ends went); 9: Levenberg-Marquardt's ray model (a re-optimization's steps); 10: each span's
  /// tightest point the tightest of its peaks, Levenberg-Marquardt's choice of model over recent steps; 11: its model
  /// always B + S, S learning only what B leaves out of the simulation's part; 12: each pose's place at rest (rest_mm);
  /// 13: each pose's sensitivity (where it goes with the silicone 10 % stiffer and softer, the pressures 10 %
  /// lower and higher); 14: the muscles' Hessian products exact, Levenberg-Marquardt's ray model taking out the
  /// barriers' expansion as its model holds it (a re-optimization's steps); 15: Levenberg-Marquardt's stall rule
  /// over the whole window (a re-optimization's ending); 16: the model's clearance-barrier Hessian from each
  /// fiber's own pairs (a re-optimization's steps); 17: Levenberg-Marquardt forgets its secant term where B + S
  /// alone claims convergence (a re-optimization's steps); 18: the skin barrier's dip term between samples (a
  /// re-optimization's objective); 19: the turn's error where a curve's orientation is tracked;
  /// 20: the exit ramp (a re-optimization's objective); 21: the ramp measured on the route as it is; 22: a straight
  /// route's bends; 23: a pose region short of its turn gets the pressures that turn it all (full_turn); 24: and
  /// whether they do (reached), the target's muscles left off; 25: each place unpressurized (its weight alone)
  int version() const override { return 25; }
  void run(StageContext& ctx) const override;
};

} // namespace fibermold
