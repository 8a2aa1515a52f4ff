#include "design/design_view.hpp"

#include <algorithm>
#include <functional>
#include <utility>

#include "design/design_file.hpp"
#include "design/undeclared_value.hpp"

namespace fibermold {

namespace {

using Copy = std::function<void(Design& to, const Design& from)>;
using Undeclare = std::function<void(Design& to)>;

/// A part of the design: a key (or a whole array section), how to copy its value, and how to make
/// it undeclared (undeclared_value.hpp).
struct Part {
  std::string key;
  Copy copy;
  Undeclare undeclare;
};

#define FIBERMOLD_PART(key, member)                                                                                    \
  Part                                                                                                                 \
  {                                                                                                                    \
    key, [](Design& to, const Design& from) { to.member = from.member; },                                              \
        [](Design& to) { make_undeclared(to.member, key); }                                                            \
  }

const std::vector<Part>& parts()
{
  static const std::vector<Part> table{
      FIBERMOLD_PART("design.name", design.name),
      FIBERMOLD_PART("design.surface", design.surface),
      Part{"design.units",
           [](Design& to, const Design& from) {
             to.design.units = from.design.units;
             to.design.surface_scale = from.design.surface_scale;
           },
           [](Design& to) {
             make_undeclared(to.design.units, "design.units");
             make_undeclared(to.design.surface_scale, "design.units");
           }},
      FIBERMOLD_PART("material.model", material.model),
      FIBERMOLD_PART("material.preset", material.preset),
      FIBERMOLD_PART("material.youngs_modulus", material.youngs_modulus),
      FIBERMOLD_PART("material.poisson_ratio", material.poisson_ratio),
      FIBERMOLD_PART("material.density", material.density),
      FIBERMOLD_PART("material.gravity", material.gravity),
      FIBERMOLD_PART("mesh.edge_length", mesh.edge_length),
      FIBERMOLD_PART("mesh.radius_edge_ratio", mesh.radius_edge_ratio),
      FIBERMOLD_PART("mesh.min_dihedral_deg", mesh.min_dihedral_deg),
      FIBERMOLD_PART("mesh.max_tets", mesh.max_tets),
      FIBERMOLD_PART("mesh.repair", mesh.repair),
      FIBERMOLD_PART("mesh.surface_triangles", mesh.surface_triangles),
      FIBERMOLD_PART("sim.basis", sim.basis),
      FIBERMOLD_PART("sim.mls_radius", sim.mls_radius),
      FIBERMOLD_PART("sim.quadrature_points", sim.quadrature_points),
      FIBERMOLD_PART("fixed", fixed),
      FIBERMOLD_PART("muscle.diameter", muscle.model.diameter),
      FIBERMOLD_PART("muscle.max_pressure", muscle.max_pressure),
      FIBERMOLD_PART("muscle.min_bend_radius", muscle.min_bend_radius),
      FIBERMOLD_PART("muscle.segments_per_mm", muscle.segments_per_length),
      FIBERMOLD_PART("muscle.stiffness", muscle.model.stiffness),
      FIBERMOLD_PART("muscle.taut", muscle.model.taut),
      FIBERMOLD_PART("muscle.rest_strain_slope", muscle.model.rest_strain_slope),
      FIBERMOLD_PART("muscle.rest_strain_intercept", muscle.model.rest_strain_intercept),
      FIBERMOLD_PART("muscle.smoothing", muscle.model.smoothing),
      FIBERMOLD_PART("fiber", fibers),
      FIBERMOLD_PART("tracking_curve", tracking_curves),
      FIBERMOLD_PART("target", targets),
      FIBERMOLD_PART("optimize.enabled", optimize.enabled),
      FIBERMOLD_PART("optimize.strategy", optimize.strategy),
      FIBERMOLD_PART("optimize.method", optimize.method),
      FIBERMOLD_PART("optimize.max_iterations", optimize.max_iterations),
      FIBERMOLD_PART("optimize.route_only_iterations", optimize.route_only_iterations),
      FIBERMOLD_PART("optimize.starts", optimize.starts),
      FIBERMOLD_PART("optimize.gradient_tolerance", optimize.gradient_tolerance),
      FIBERMOLD_PART("optimize.relative_tolerance", optimize.relative_tolerance),
      FIBERMOLD_PART("optimize.decrease_tolerance", optimize.decrease_tolerance),
      FIBERMOLD_PART("optimize.weight_curvature", optimize.weight_curvature),
      FIBERMOLD_PART("optimize.weight_skin_barrier", optimize.weight_skin_barrier),
      FIBERMOLD_PART("optimize.weight_bend_barrier", optimize.weight_bend_barrier),
      FIBERMOLD_PART("optimize.weight_pressure_barrier", optimize.weight_pressure_barrier),
      FIBERMOLD_PART("optimize.refine", optimize.refine),
      FIBERMOLD_PART("collide.clearance", collide.clearance),
      FIBERMOLD_PART("collide.smoothness", collide.smoothness),
      FIBERMOLD_PART("collide.samples_per_mm", collide.samples_per_length),
      FIBERMOLD_PART("collide.reoptimize", collide.reoptimize),
      FIBERMOLD_PART("mold.wall", mold.block.wall),
      FIBERMOLD_PART("mold.voxel", mold.voxel),
      FIBERMOLD_PART("mold.pull", mold.pull),
      FIBERMOLD_PART("mold.parting", mold.parting),
      FIBERMOLD_PART("mold.keys", mold.block.keys),
      FIBERMOLD_PART("mold.key_shape", mold.block.key_shape),
      FIBERMOLD_PART("mold.key_diameter", mold.block.key_diameter),
      FIBERMOLD_PART("mold.key_clearance", mold.block.key_clearance),
      FIBERMOLD_PART("mold.sprue_diameter", mold.block.sprue_diameter),
      FIBERMOLD_PART("mold.vents", mold.block.vents),
      FIBERMOLD_PART("mold.vent_diameter", mold.block.vent_diameter),
      FIBERMOLD_PART("mold.groove_clearance", mold.groove_clearance),
      FIBERMOLD_PART("mold.min_silicone", mold.min_silicone),
      FIBERMOLD_PART("mold.end_channel_length", mold.end_channel_length),
      FIBERMOLD_PART("mold.end_channel_diameter", mold.end_channel_diameter),
      FIBERMOLD_PART("mold.screw_holes", mold.block.screw_holes),
      FIBERMOLD_PART("mold.screw_diameter", mold.block.screw_diameter),
      FIBERMOLD_PART("mold.draft_deg", mold.draft_deg),
      FIBERMOLD_PART("mold.labels", mold.labels),
      FIBERMOLD_PART("mold.shrink", mold.shrink),
      FIBERMOLD_PART("export.formats", export_.formats),
      FIBERMOLD_PART("export.printer_volume", export_.printer_volume),
      FIBERMOLD_PART("export.min_wall", export_.min_wall),
  };
  return table;
}

#undef FIBERMOLD_PART

} // namespace

bool view_part_under(const std::string& part, const std::string& prefix)
{
  return part == prefix || (part.size() > prefix.size() && part.starts_with(prefix) && part[prefix.size()] == '.');
}

Design design_view(const Design& design, const std::vector<std::string>& prefixes)
{
  Design view;
  view.file = design.file;
  view.folder = design.folder;
  view.places = design.places;
  // Every part undeclared first, then the declared ones copied: a row that copies another's member
  // shows in that member, whatever the order of the rows.
  for (const Part& part : parts()) part.undeclare(view);
  for (const Part& part : parts())
    if (std::any_of(prefixes.begin(), prefixes.end(),
                    [&](const std::string& prefix) { return view_part_under(part.key, prefix); }))
      part.copy(view, design);
  for (const auto& [key, value] : design.values)
    for (const std::string& prefix : prefixes)
      if (design_key_matches(key, prefix)) {
        view.values[key] = value;
        break;
      }
  return view;
}

std::vector<std::string> design_view_parts()
{
  std::vector<std::string> keys;
  for (const Part& p : parts()) keys.push_back(p.key);
  return keys;
}

} // namespace fibermold
