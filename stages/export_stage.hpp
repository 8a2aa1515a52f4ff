#pragma once
// The export stage: the mold parts as the printer needs them. Each part of the molds stage is laid
// flat on its largest planar face and written as a binary STL (and 3MF when asked) in mm;
// manifest.json lists every part (files, bounding box, volume, triangles, checks) and each shot's
// silicone volume and mass; README.txt says how to cast; report.html shows the parts and the fibers
// in 3D with the checks and the stage timings. Outputs in <build>/export/.

#include "make/stage.hpp"

namespace fibermold {

class ExportStage final : public Stage {
public:
  std::string name() const override { return "export"; }
  std::vector<std::string> upstream() const override { return {"mesh", "targets", "optimize", "collide", "molds"}; }
  /// The report shows the tracking curves and names the targets; README.txt gives the silicone (material), the
  /// muscles' diameter and max pressure, feeds each muscle from its end nearest the mount (fixed) through its end
  /// channel (mold.end_channel_diameter and end_channel_length: the socket the supply tube's fitting sits in).
  std::vector<std::string> design_keys() const override
  {
    return {"design.name",
            "export",
            "material",
            "fixed",
            "muscle",
            "tracking_curve",
            "target",
            "mold.labels",
            "mold.end_channel_diameter",
            "mold.end_channel_length",
            "mold.screw_diameter",
            "mold.draft_deg"};
  }
  /// 2: the fill in the manifest and README.txt, parts' transforms; 3: no timings in report.html; 4: the optimization
  /// table and the warnings banner; 5: each target drawn beside the robot, the turns reached; 6: the bend radius
  /// table; 7: deformed-<target>.stl and how to check the cast robot with it; 8: the casting sheet (silicone, muscles);
  /// 9: the sprues and vents in the 3D view; 10: the countersunk sprue in README.txt; 11: the parts' labels in
  /// README.txt and the manifest; 12: the labels in report.html's parts table, README.txt without them when [mold]
  /// labels = false; 13: README.txt: the print material, the side each half holds, release on the molds only, gauge
  /// pressures, the default silicone's preset E; 14: at least 5 g of each part mixed; 15: the optimization's warnings
  /// in README.txt; 16: the casting sheet's steps wrapped within 100 characters whatever the counts of holes; 17: when
  /// to fit and seal the muscles and the supply tube's width, the poses to compare wrapped, "reached" explained; 18:
  /// which figure to measure on the cast robot, and what it is with the silicone and the pressures 10 % off; 19: the
  /// same in report.html; 20: how to mount the robot to check it (gravity's direction); 21: a region's turn is its
  /// nodes' fit, the higher pressure said to be above max_pressure where it is; 23: the modulus to the pascal, as the
  /// simulation used it; 24: report.html: the first guess's RMSE and the turn's error beside the optimized figures;
  /// 25: README.txt: where the robot is held, the spacers under shot 1, tubes threaded through the upper half;
  /// report.html: a kept first guess said in the optimization table's title; 26: README.txt: what pressures turn a
  /// pose region short of its turn all the way (collide's full_turn); 27: the supply tube's hole as wide as the
  /// muscle, a full turn short of the angle said so, the command that shows it; 28: the figure to measure before
  /// the robot is pressurized (its weight alone); 29: report.html: the plots' axes at round values, the check
  /// table's figure unpressurized and at the whole angle; 30: the optimization table's gain over the first guess at
  /// its best pressures; 31: the socket's length in README.txt read from the design (it read an undeclared key: NaN);
  /// 32: the halves with thin deep ribs printed solid, the screw holes' bolts, the muscle–tube joint, only the mold
  /// parts printed as they lie; 33: how to measure the figure (photographs along the axis, or beside a ruler); 34:
  /// the muscles tacked to the grooves' bottoms before shot 2; 35: tacked beside them, the bolts within ISO 273's
  /// coarse clearance, how to measure after the rigid-fit sentence
  int version() const override { return 35; }
  void run(StageContext& ctx) const override;
};

} // namespace fibermold
