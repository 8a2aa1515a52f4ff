#include "stages/design_mesh.hpp"

#include <chrono>
#include <vector>

#include <fmt/format.h>

#include "core/elapsed.hpp"
#include "core/input_error.hpp"
#include "core/units.hpp"
#include "mesh/surface_import.hpp"

namespace fibermold {

namespace {

using Clock = std::chrono::steady_clock;

/// A closed void inside the body cannot be cast in a two-part mold: nothing would hold it open
/// (it takes a core, which fibermold does not make).
void require_castable(const SurfaceCheck& check, const SurfaceMesh& surface)
{
  std::vector<Diagnostic> diagnostics;
  for (const SurfaceCavity& c : check.cavities)
    diagnostics.push_back(
        {surface.source, 0, 0, "",
         fmt::format("surface {} has a closed internal cavity of {:.4g} mm³ around ({:.1f}, {:.1f}, {:.1f}) mm: a "
                     "two-part mold cannot cast it (the void would need a core to hold it, which fibermold does "
                     "not make). Fill it; or open it through the skin toward [mold] pull, as wide as it is across, "
                     "so that a mold half forms it as a pocket (a narrower inlet, or one to the side, leaves a core "
                     "that no half can pull out), and close it after casting (bond on a cap) if it must hold air; "
                     "or make the chamber otherwise (a wax or soluble core, or the body cast in two parts and "
                     "bonded)",
                     surface.source.filename().string(), c.volume / units::mm3, c.centre.x() / units::mm,
                     c.centre.y() / units::mm, c.centre.z() / units::mm)});
  if (!diagnostics.empty()) throw InputError(std::move(diagnostics));
}

} // namespace

double require_mesh_size(const Design& d, const SurfaceMesh& surface, double volume, double edge,
                         SurfaceTriangles policy, MeshOf of)
{
  const double tets = expected_tets(volume, edge, policy, surface);
  const bool refined = of == MeshOf::refinement;
  if (tets > d.mesh.max_tets)
    throw InputError(design_problem(
        d, refined ? "[optimize].refine" : "[mesh].edge_length",
        fmt::format("{}{:.4g} mm for a body of {:.4g} mm³ would make about {:.3g} tets, more than "
                    "[mesh].max_tets = {}; {}",
                    refined ? "the refined mesh's edge length, " : "", edge / units::mm, volume / units::mm3, tets,
                    d.mesh.max_tets,
                    refined ? "raise max_tets or turn refine off" : "raise edge_length, or check [design].units")));
  return tets;
}

SurfaceTriangles refined_policy(const Design& d, const SurfaceMesh& surface, double edge)
{
  const SurfaceTriangles policy =
      d.mesh.surface_triangles == SurfaceTriangles::remesh ? SurfaceTriangles::remesh : SurfaceTriangles::automatic;
  return surface_treatment(policy, surface, edge) == SurfaceTriangles::keep ? SurfaceTriangles::split : policy;
}

SurfaceMesh prepared_surface(const Design& d, SurfaceCheck& check, RepairReport& repair, nlohmann::json& seconds)
{
  auto t = Clock::now();
  SurfaceMesh surface = import_surface(d.design.surface, d.design.surface_scale);
  seconds["import"] = since(t);
  t = Clock::now();
  check = check_surface(surface);
  seconds["check"] = since(t);
  if (d.mesh.repair) {
    t = Clock::now();
    surface = repair_surface(surface, {}, repair);
    check = check_surface(surface);
    seconds["repair"] = since(t);
  }
  require_valid_surface(check, surface, d.mesh.repair);
  require_castable(check, surface);
  return surface;
}

TetOptions tet_options(const Design& d, double edge)
{
  return {edge, d.mesh.radius_edge_ratio, d.mesh.min_dihedral_deg, d.sim.basis == BasisKind::fem_p2, true};
}

double target_edge_length(const Design& design, double body_volume)
{
  return design.mesh.edge_length ? *design.mesh.edge_length : default_edge_length(body_volume);
}

namespace {
/// The refined mesh's edge length: kRefinedEdgeFactor of the body mesh's.
double refined_edge_length(const Design& d, double volume)
{
  return kRefinedEdgeFactor * target_edge_length(d, volume);
}
} // namespace

double require_refined_mesh_size(const Design& d, const SurfaceMesh& surface, double volume)
{
  const double edge = refined_edge_length(d, volume);
  return require_mesh_size(d, surface, volume, edge, refined_policy(d, surface, edge), MeshOf::refinement);
}

TetMesh refined_design_mesh(const Design& d, Progress& progress)
{
  SurfaceCheck check;
  RepairReport repair;
  nlohmann::json seconds;
  const SurfaceMesh surface = prepared_surface(d, check, repair, seconds);
  return refined_design_mesh(d, surface, check.volume, progress);
}

TetMesh refined_design_mesh(const Design& d, const SurfaceMesh& surface, double volume, Progress& progress)
{
  const double edge = refined_edge_length(d, volume);
  const SurfaceTriangles policy = refined_policy(d, surface, edge);
  require_mesh_size(d, surface, volume, edge, policy, MeshOf::refinement);
  return mesh_body(surface, policy, tet_options(d, edge), progress).mesh;
}

} // namespace fibermold
