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
  int version() const override { return 3; }  ///< 2: the surface's triangles split where too large; edge lengths, quality bounds and the surface's deviation in the report; 3: dense surfaces remeshed, surface places in body.tetmesh
  void run(StageContext& ctx) const override;
};

/// What `fibermold check` says about the surface: imports and checks it (and, with
/// [mesh] repair = true, checks the repaired copy). Throws InputError when it cannot be meshed.
SurfaceCheck check_design_surface(const Design& design, std::vector<std::string>& repairs);

/// Target edge length: [mesh] edge_length, or one that fits about 5,000 regular tets in the body.
double target_edge_length(const Design& design, double body_volume);

/// The body meshed as the mesh stage meshes it, at `edge_factor` × its edge length, the surface's
/// triangles split to that length (`fibermold simulate --refine`). Throws InputError as the stage.
TetMesh scaled_design_mesh(const Design& design, double edge_factor, Progress& progress);

} // namespace fibermold
