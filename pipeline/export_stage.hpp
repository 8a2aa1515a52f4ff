#pragma once
// The export stage: the mold parts as the printer needs them. Each part of the molds stage is laid
// flat on its largest planar face and written as a binary STL in mm; manifest.json lists every
// part (file, bounding box, volume, triangles, checks) and each shot's silicone volume and mass;
// README.txt says how to cast. Outputs in <build>/export/.

#include "pipeline/stage.hpp"

namespace fibermold {

class ExportStage final : public Stage {
public:
  std::string name() const override { return "export"; }
  std::vector<std::string> upstream() const override { return {"molds"}; }
  std::vector<std::string> design_keys() const override { return {"design.name", "export"}; }
  void run(StageContext& ctx) const override;
};

} // namespace fibermold
