#include "stages/stages.hpp"

#include "stages/collide_stage.hpp"
#include "stages/export_stage.hpp"
#include "stages/mesh_stage.hpp"
#include "stages/molds_stage.hpp"
#include "stages/optimize_stage.hpp"
#include "stages/targets_stage.hpp"

namespace fibermold {

// Only real stages are registered here; each arrives with its module (mesh, targets, optimize,
// collide, molds, export).
std::vector<std::unique_ptr<Stage>> shipped_stages()
{
  std::vector<std::unique_ptr<Stage>> stages;
  stages.push_back(std::make_unique<MeshStage>());
  stages.push_back(std::make_unique<TargetsStage>());
  stages.push_back(std::make_unique<OptimizeStage>());
  stages.push_back(std::make_unique<CollideStage>());
  stages.push_back(std::make_unique<MoldsStage>());
  stages.push_back(std::make_unique<ExportStage>());
  return stages;
}

} // namespace fibermold
