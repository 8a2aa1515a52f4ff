#include "stages/check.hpp"

#include <nlohmann/json.hpp>

#include "mesh/surface_distance.hpp"
#include "mesh/surface_repair.hpp"
#include "stages/design_mesh.hpp"
#include "stages/design_simulation.hpp"
#include "stages/molds_stage.hpp"
#include "stages/optimize_stage.hpp"
#include "stages/routing_evaluation.hpp"
#include "stages/targets_stage.hpp"

namespace fibermold {

DesignSurfaceCheck check_design_surface(const Design& design)
{
  DesignSurfaceCheck c;
  SurfaceCheck& check = c.surface;
  RepairReport repair;
  nlohmann::json seconds;
  const SurfaceMesh surface = prepared_surface(design, check, repair, seconds);
  c.repairs = repair.changes();
  c.lo = surface.vertices.colwise().minCoeff();
  c.hi = surface.vertices.colwise().maxCoeff();
  // What the stages would refuse later for their size, refused now; and a remeshing that the
  // body's features cannot take.
  const double edge = target_edge_length(design, check.volume);
  c.edge_length = edge;
  c.treatment = surface_treatment(design.mesh.surface_triangles, surface, edge);
  c.estimated_tets = require_mesh_size(design, surface, check.volume, edge, design.mesh.surface_triangles);
  if (design.optimize.enabled && design.optimize.refine) require_refined_mesh_size(design, surface, check.volume);
  const MeshedSurface meshed = surface_for_mesh(surface, design.mesh.surface_triangles, edge);
  std::vector<std::vector<Eigen::Vector3d>> fibers;
  for (const Fiber& f : design.fibers) fibers.push_back(f.points);
  require_mold_grids(design, surface, fibers);
  require_molds_fit_printer(design, surface);
  // The fibers against the skin the optimizer will see: the mesh's (remeshed, when it is).
  require_optimizable(design, SurfaceDistance(meshed.surface.vertices, meshed.surface.faces));
  require_bend_radius(design, starting_routing(design).routes, "the starting route", true);
  require_regions_reach_the_body(design, surface);
  for (const Target& t : design.targets)
    if (t.kind == TargetKind::surface) read_target_surface(design, t, surface.num_vertices(), surface.faces);
  return c;
}

} // namespace fibermold
