#pragma once
// The targets stage (paper section V): each [[target]] becomes a target deformation of the body.
//   forces:  forward simulation under the loads;
//   fibers:  forward simulation with the given fibers and pressures (a known solution);
//   surface: a deformed copy of the body's surface, filled in volumetrically by a simulation with
//            soft Dirichlet conditions on every surface vertex (Fig. 4).
// Outputs: targets/<name>.vtu (ParaView), targets/<name>.positions (nodal state for optimize),
// targets/report.json.

#include "make/stage.hpp"

namespace fibermold {

class TargetsStage final : public Stage {
public:
  std::string name() const override { return "targets"; }
  std::vector<std::string> upstream() const override { return {"mesh"}; }
  std::vector<std::string> design_keys() const override
  {
    return {"design.units", "material", "sim", "fixed", "muscle", "fiber", "target"};
  }
  std::vector<std::filesystem::path> input_files(const Design& d) const override;
  void run(StageContext& ctx) const override;
};

} // namespace fibermold
