#pragma once
// The body of a design meshed as the mesh stage meshes it, shared by the mesh stage, `fibermold
// check`, optimize's refined mesh and `fibermold simulate --refine`: the surface prepared
// (imported, checked, repaired on request), the edge length, the size refused before meshing, and
// the refined mesh.

#include <string>

#include <nlohmann/json.hpp>

#include "core/progress.hpp"
#include "design/design.hpp"
#include "mesh/body_mesh.hpp"
#include "mesh/surface_check.hpp"
#include "mesh/surface_repair.hpp"
#include "mesh/tet_mesh.hpp"

namespace fibermold {

/// Which mesh a size is asked of: the body's (the mesh stage's, at [mesh] edge_length) or the
/// refined one ([optimize] refine's, and simulate --refine's), each refused with its own key and fix.
enum class MeshOf { body, refinement };

/// Refuses an edge length that would make more than [mesh] max_tets tets (wrong units, typically),
/// before any remeshing or TetGen run can take all memory. Returns the estimate (expected_tets).
double require_mesh_size(const Design& d, const SurfaceMesh& surface, double volume, double edge,
                         SurfaceTriangles policy, MeshOf of = MeshOf::body);

/// The surface treatment of the refined mesh (optimize's and simulate's refine) at `edge`: remeshed
/// where the design remeshes it or it is dense for the edge, split otherwise (its own triangles
/// kept would hold the mesh at their size).
SurfaceTriangles refined_policy(const Design& d, const SurfaceMesh& surface, double edge);

/// Import, check, and repair when asked, with each step's seconds in `seconds`; throws InputError
/// when the result cannot be meshed or cast (a closed internal cavity).
SurfaceMesh prepared_surface(const Design& d, SurfaceCheck& check, RepairReport& repair, nlohmann::json& seconds);

/// TetGen's options for the design at `edge` (mesh_body sets whether the surface is kept).
TetOptions tet_options(const Design& d, double edge);

/// Target edge length: [mesh] edge_length, or one that fits about 5,000 regular tets in the body.
double target_edge_length(const Design& design, double body_volume);

/// The refined mesh's edge length, × the mesh's (`[optimize] refine`, `fibermold simulate --refine`).
inline constexpr double kRefinedEdgeFactor = 0.5;

/// The refined mesh's size (`[optimize] refine`) as check and the optimize stage both judge it:
/// its tets estimated at kRefinedEdgeFactor × the edge length with refined_policy's surface,
/// refused over [mesh] max_tets under the key [optimize].refine. Returns the estimate.
double require_refined_mesh_size(const Design& d, const SurfaceMesh& surface, double volume);

/// The body meshed as the mesh stage meshes it, at kRefinedEdgeFactor × its edge length, the
/// surface's triangles split or remeshed to that length. Throws InputError as the stage.
TetMesh refined_design_mesh(const Design& design, Progress& progress);
/// The same from the body's surface as prepared_surface gave it and its volume.
TetMesh refined_design_mesh(const Design& design, const SurfaceMesh& surface, double volume, Progress& progress);

} // namespace fibermold
