#pragma once
// The mesh stage: import the body's surface, check it, repair it on request, tetrahedralize it.
// Outputs: mesh/body.tetmesh (for later stages), mesh/body.vtu (ParaView), mesh/report.json.

#include <string>
#include <vector>

#include "make/stage.hpp"
#include "mesh/surface_check.hpp"
#include "mesh/tet_mesh.hpp"

namespace fibermold {

class MeshStage final : public Stage {
public:
  std::string name() const override { return "mesh"; }
  std::vector<std::string> design_keys() const override
  {
    return {"design.surface", "design.units", "mesh", "sim.basis"};
  }
  std::vector<std::filesystem::path> input_files(const Design& d) const override;
  /// 2: the surface's triangles split where too large; edge lengths, quality bounds and the surface's deviation in
  /// the report; 3: dense surfaces remeshed, surface places in body.tetmesh; 4: the mesh made at the edge length asked
  /// (TetGen's volume bound rescaled), sizing and the tet estimate in the report
  int version() const override { return 4; }
  void run(StageContext& ctx) const override;
};

} // namespace fibermold
