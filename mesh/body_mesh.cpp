#include "mesh/body_mesh.hpp"

#include <fmt/format.h>

#include "core/input_error.hpp"
#include "core/units.hpp"
#include "mesh/surface_check.hpp"
#include "mesh/surface_places.hpp"

namespace fibermold {

namespace {

/// A remeshing that made the surface invalid (a thin web's two sides met): the user's edge length
/// is too coarse for the body's features.
void require_valid_remeshing(const SurfaceMesh& input, const SurfaceMesh& remeshed, double edge_length)
{
  const SurfaceCheck check = check_surface(remeshed);
  if (check.ok()) return;
  const SurfaceProblem& p = check.problems.front();
  throw InputError(std::vector<Diagnostic>{{input.source, 0, 0, "",
                     fmt::format("remeshed at {:.4g} mm edges, surface {} {} near {}: its features are thinner than the edge length "
                                 "there; give a smaller [mesh] edge_length, or surface_triangles = \"split\" (or \"keep\") "
                                 "to mesh the input's own triangles",
                                 edge_length / units::mm, input.source.filename().string(), p.message, format_mm(p.where))}});
}

} // namespace

MeshedSurface surface_for_mesh(const SurfaceMesh& input, SurfaceTriangles policy, double edge_length)
{
  MeshedSurface m;
  m.treatment = surface_treatment(policy, input, edge_length);
  if (m.treatment != SurfaceTriangles::remesh) {
    m.surface = input;
    return m;
  }
  m.surface = remesh_surface(input, edge_length, m.remeshing);
  require_valid_remeshing(input, m.surface, edge_length);
  return m;
}

TetMesh mesh_body(const SurfaceMesh& input, const MeshedSurface& meshed, TetOptions options, Progress& progress)
{
  options.keep_surface = meshed.treatment != SurfaceTriangles::split;
  TetMesh mesh = tetrahedralize(meshed.surface, options, progress);
  if (meshed.treatment == SurfaceTriangles::remesh) attach_to_surface(mesh, input);
  return mesh;
}

} // namespace fibermold
