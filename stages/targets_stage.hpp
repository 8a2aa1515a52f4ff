#pragma once
// The targets stage (paper section V): each [[target]] becomes a target deformation of the body.
//   forces:  forward simulation under the loads;
//   fibers:  forward simulation with the given fibers and pressures (a known solution);
//   surface: a deformed copy of the body's surface, filled in volumetrically by a simulation with
//            soft Dirichlet conditions on every surface vertex (Fig. 4);
//   pose:    regions moved by rigid motions, the rest following under gravity and [[fixed]].
// Every target's report gives the pose (translation, rotation) its regions and the tracking
// curves' ends reach.
// Outputs: targets/<name>.vtu (ParaView), targets/<name>.positions (nodal state for optimize),
// targets/<name>.json (the deformed nodes in mm, for report.html), targets/report.json.

#include "make/stage.hpp"
#include "mesh/surface_mesh.hpp"

namespace fibermold {

/// A `kind = "surface"` target's file, held against the body's input surface (its vertex count and
/// faces): InputError when it is not a deformed copy of it. `check` asks it too.
SurfaceMesh read_target_surface(const Design& d, const Target& t, Eigen::Index vertices, const Eigen::MatrixX3i& faces);

class TargetsStage final : public Stage {
public:
  std::string name() const override { return "targets"; }
  std::vector<std::string> upstream() const override { return {"mesh"}; }
  int version() const override
  {
    return 3;
  } ///< 2: pose targets, each target's reached poses in the report; 3: <name>.json
  std::vector<std::string> design_keys() const override
  {
    return {"design.units", "material", "sim", "fixed", "muscle", "fiber", "tracking_curve", "target"};
  }
  /// Without a kind = "fibers" target, neither `fiber` nor `muscle`: a route's edit leaves the
  /// targets fresh (a new user's jaw re-ran its two pose targets, 8 s, at every route edit).
  std::vector<std::string> design_keys_used(const Design& d) const override;
  std::vector<std::filesystem::path> input_files(const Design& d) const override;
  void run(StageContext& ctx) const override;
};

} // namespace fibermold
