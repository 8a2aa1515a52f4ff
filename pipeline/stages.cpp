#include "pipeline/stages.hpp"

#include "pipeline/collide_stage.hpp"
#include "pipeline/export_stage.hpp"
#include "pipeline/mesh_stage.hpp"
#include "pipeline/molds_stage.hpp"
#include "pipeline/optimize_stage.hpp"
#include "pipeline/targets_stage.hpp"

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
