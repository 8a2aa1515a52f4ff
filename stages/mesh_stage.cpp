#include "stages/mesh_stage.hpp"

#include <chrono>
#include <cmath>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

#include "core/atomic_file.hpp"
#include "core/elapsed.hpp"
#include "core/input_error.hpp"
#include "core/json_file.hpp"
#include "core/units.hpp"
#include "export/vtu_writer.hpp"
#include "mesh/body_mesh.hpp"
#include "mesh/mesh_quality.hpp"
#include "mesh/surface_distance.hpp"
#include "mesh/surface_import.hpp"
#include "mesh/surface_repair.hpp"
#include "mesh/volume_tolerance.hpp"
#include "stages/design_mesh.hpp"

namespace fibermold {

namespace {

using Clock = std::chrono::steady_clock;

/// The share of tets outside the quality bounds above which the mesh stage warns.
constexpr double kQualityMissWarning = 0.01;

nlohmann::json point_mm(const Eigen::Vector3d& p) { return {p.x() / units::mm, p.y() / units::mm, p.z() / units::mm}; }

/// How far the mesh's surface is from the input's. Split: the points TetGen added on it (they lie
/// on its triangles, 0 up to round-off). Remeshed: both ways, and the input vertices farther than
/// kFeatureLoss × the edge length from the mesh's surface (a feature the edge length cannot hold).
struct SurfaceFollowing {
  Eigen::Index points_added = 0;
  double deviation = 0; ///< m, the largest distance either way
  SurfaceDeviation remeshed;
};
constexpr double kFeatureLoss = 0.25;
SurfaceFollowing surface_following(const SurfaceMesh& input, const MeshedSurface& meshed, const TetMesh& mesh,
                                   double edge)
{
  SurfaceFollowing f;
  if (meshed.treatment == SurfaceTriangles::remesh) {
    f.remeshed = surface_deviation(input, meshed.surface, kFeatureLoss * edge);
    f.deviation = std::max(f.remeshed.remeshed_from_input, f.remeshed.input_from_remeshed);
    return f;
  }
  std::vector<bool> on_surface(static_cast<std::size_t>(mesh.nodes.rows()), false);
  for (Eigen::Index i = 0; i < mesh.boundary_faces.size(); ++i)
    on_surface[static_cast<std::size_t>(mesh.boundary_faces(i))] = true;
  const SurfaceDistance distance(input.vertices, input.faces);
  for (Eigen::Index v = input.num_vertices(); v < mesh.nodes.rows(); ++v) {
    if (!on_surface[static_cast<std::size_t>(v)]) continue;
    ++f.points_added;
    f.deviation = std::max(f.deviation, distance.closest(mesh.nodes.row(v).transpose()).distance);
  }
  return f;
}

/// The surface's part of the mesh report: the policy, what was done, and how far from the input.
nlohmann::ordered_json surface_triangles_report(const Design& d, const SurfaceMesh& input, const MeshedSurface& meshed,
                                                const SurfaceFollowing& f)
{
  nlohmann::ordered_json r = {{"policy", choice_name(d.mesh.surface_triangles)},
                              {"treatment", choice_name(meshed.treatment)},
                              {"split", meshed.treatment == SurfaceTriangles::split},
                              {"input_longest_edge_mm", longest_edge(input) / units::mm},
                              {"input_mean_edge_mm", mean_edge_length(input) / units::mm},
                              {"points_added", f.points_added},
                              {"deviation_mm", f.deviation / units::mm}};
  if (meshed.treatment == SurfaceTriangles::remesh)
    r["remeshed"] = {{"input_faces", input.num_faces()},
                     {"faces", meshed.surface.num_faces()},
                     {"mean_edge_mm", mean_edge_length(meshed.surface) / units::mm},
                     {"sharp_edges_kept", meshed.remeshing.sharp_edges},
                     {"volume_change", signed_volume(meshed.surface) / signed_volume(input) - 1},
                     {"mesh_from_input_mm", f.remeshed.remeshed_from_input / units::mm},
                     {"input_from_mesh_mm", f.remeshed.input_from_remeshed / units::mm},
                     {"input_vertices_off", f.remeshed.input_vertices_beyond},
                     {"worst_at_mm", point_mm(f.remeshed.worst_at)}};
  return r;
}

void log_treatment(StageContext& ctx, const SurfaceMesh& input, const BodyMesh& body, double edge)
{
  const MeshedSurface& meshed = body.surface;
  if (body.sizing.first_treatment != meshed.treatment) {
    ctx.log.info(
        "surface: with its triangles {} the mesh came out finer than asked (its own vertices hold it); remeshed to the "
        "edge length instead, {} → {} faces ({} sharp edges kept)",
        body.sizing.first_treatment == SurfaceTriangles::split ? "split" : "kept", input.num_faces(),
        meshed.surface.num_faces(), meshed.remeshing.sharp_edges);
    return;
  }
  if (meshed.treatment == SurfaceTriangles::split)
    ctx.log.info("surface: its longest edge is {:.3g} mm, {:.2g}× the edge length: TetGen splits its triangles to the "
                 "edge length",
                 longest_edge(input) / units::mm, longest_edge(input) / edge);
  if (meshed.treatment == SurfaceTriangles::remesh)
    ctx.log.info("surface: its mean edge is {:.3g} mm, {:.2g}× the edge length: remeshed to it, {} → {} faces ({} "
                 "sharp edges kept)",
                 mean_edge_length(input) / units::mm, mean_edge_length(input) / edge, input.num_faces(),
                 meshed.surface.num_faces(), meshed.remeshing.sharp_edges);
  // Kept triangles well under the edge length hold the mesh finer than asked (auto remeshes below 0.5×).
  if (meshed.treatment == SurfaceTriangles::keep && mean_edge_length(input) < 0.75 * edge)
    ctx.log.warn("surface: its triangles are kept and their mean edge, {:.3g} mm, is {:.2g}× the edge length: the mesh "
                 "comes out "
                 "finer than asked (slower, not less accurate); surface_triangles = \"remesh\" coarsens it to [mesh] "
                 "edge_length",
                 mean_edge_length(input) / units::mm, mean_edge_length(input) / edge);
}

/// How the mesh came to the edge length: TetGen's volume bound rescaled, or a warning where the edge
/// length made still misses.
void log_sizing(StageContext& ctx, const BodyMesh& body, double edge)
{
  const MeshSizing& s = body.sizing;
  if (s.tetgen_runs > 1)
    ctx.log.info("mesh: TetGen's volume bound at {:.3g}× a regular {:.3g} mm tet's gives a mean edge of {:.3g} mm ({} "
                 "runs of TetGen)",
                 s.volume_bound_factor, edge / units::mm, s.mean_edge_length / units::mm, s.tetgen_runs);
  if (std::abs(s.mean_edge_length / edge - 1) > kEdgeLengthTolerance)
    ctx.log.warn("mesh: its mean edge, {:.3g} mm, is {:.2f}× the {:.3g} mm asked ([mesh] edge_length): {}",
                 s.mean_edge_length / units::mm, s.mean_edge_length / edge, edge / units::mm,
                 s.mean_edge_length < edge
                     ? "the surface's own triangles or features hold it finer (slower, not less accurate); "
                       "surface_triangles = \"remesh\" coarsens them to the edge length"
                     : "the surface's triangles are coarser than asked; surface_triangles = \"split\" or "
                       "\"remesh\" refines them");
}

/// A remeshing that moved the surface by more than kFeatureLoss × the edge length somewhere: a
/// feature (a thin web, a notch, a small hole) the edge length cannot hold, named by place.
void warn_lost_features(StageContext& ctx, const MeshedSurface& meshed, const SurfaceFollowing& f, double edge)
{
  if (meshed.treatment != SurfaceTriangles::remesh || f.remeshed.input_vertices_beyond == 0) return;
  ctx.log.warn(
      "surface: remeshed at {:.3g} mm edges, {} input vertices lie more than {:.3g} mm from the mesh's surface (up to "
      "{:.3g} mm, near {}): features smaller than the edge length are lost there; a smaller [mesh] edge_length keeps "
      "them, or surface_triangles = \"split\" meshes the input's own triangles",
      edge / units::mm, f.remeshed.input_vertices_beyond, kFeatureLoss * edge / units::mm,
      f.remeshed.input_from_remeshed / units::mm, format_mm(f.remeshed.worst_at));
}

/// TetGen's mesh checked: no inverted tet, the volume of the surface it was given (to
/// volume_tolerance), and a warning when more than kQualityMissWarning of the tets miss the quality
/// bounds.
void require_sound_mesh(const Design& d, StageContext& ctx, const TetMesh& mesh, const MeshQuality& q,
                        const MeshedSurface& meshed, const SurfaceFollowing& following)
{
  if (q.inverted_tets > 0) throw std::runtime_error(fmt::format("TetGen produced {} inverted tets", q.inverted_tets));
  const bool split = meshed.treatment == SurfaceTriangles::split;
  // TetGen's dihedral bound is best effort: a few slivers (0.04–0.5 % of the examples' tets) are
  // reported, not warned about; more than 1 % is a mesh to look at.
  if (q.over_ratio + q.under_dihedral > kQualityMissWarning * static_cast<double>(mesh.num_tets()))
    ctx.log.warn("mesh: {} of {} tets exceed the radius-edge ratio bound {} (up to {:.3g}, near {}) and {} have a "
                 "dihedral angle "
                 "under {}°{}",
                 q.over_ratio, mesh.num_tets(), d.mesh.radius_edge_ratio, q.max_radius_edge_ratio,
                 format_mm(q.worst_at), q.under_dihedral, d.mesh.min_dihedral_deg,
                 split ? ""
                       : ": TetGen cannot meet its bounds beside the surface's triangles, kept exactly; [mesh] "
                         "surface_triangles = "
                         "\"split\" lets it add points on the surface");
  const double expected = signed_volume(meshed.surface);
  const double tolerance = volume_tolerance(mesh, meshed.surface, split ? following.deviation : 0);
  if (std::abs(q.volume - expected) > tolerance)
    throw InputError(std::vector<Diagnostic>{
        {d.design.surface, 0, 0, "",
         fmt::format("the tet mesh does not fill the surface: its volume, {:.9g} mm³, differs from the surface's "
                     "{:.9g} mm³ by {:.3g} "
                     "mm³, more than round-off{} allows ({:.3g} mm³); TetGen lost part of the body. Try another [mesh] "
                     "edge_length, "
                     "or surface_triangles = \"{}\"",
                     q.volume / units::mm3, expected / units::mm3, std::abs(q.volume - expected) / units::mm3,
                     split ? " and the added points' distance from the surface" : "", tolerance / units::mm3,
                     meshed.treatment == SurfaceTriangles::remesh ? "split" : "remesh")}});
  ctx.log.info("mesh: volume {:.9g} mm³, the surface's to {:.2g} mm³ (round-off allows {:.2g})", q.volume / units::mm3,
               std::abs(q.volume - expected) / units::mm3, tolerance / units::mm3);
}

/// The tets for ParaView, with each one's radius-edge ratio and volume.
void write_mesh_vtu(const std::filesystem::path& path, const TetMesh& mesh)
{
  VtuGrid grid(mesh.nodes);
  grid.add_cells(mesh.tets, mesh.nodes_per_tet() == 10 ? VtkCell::quadratic_tetra : VtkCell::tetra);
  Eigen::MatrixXd ratio(mesh.num_tets(), 1), volume(mesh.num_tets(), 1);
  for (Eigen::Index i = 0; i < mesh.num_tets(); ++i) {
    const auto corner = [&](int k) { return Eigen::Vector3d(mesh.nodes.row(mesh.tets(i, k))); };
    ratio(i, 0) = radius_edge_ratio(corner(0), corner(1), corner(2), corner(3));
    volume(i, 0) = mesh.tet_volume(i) / units::mm3;
  }
  grid.add_cell_field("radius_edge_ratio", ratio);
  grid.add_cell_field("volume_mm3", volume);
  grid.write(path);
}

} // namespace

std::vector<std::filesystem::path> MeshStage::input_files(const Design& d) const
{
  return surface_files(d.design.surface);
}

void MeshStage::run(StageContext& ctx) const
{
  const Design& d = ctx.design;
  const auto start = Clock::now();
  nlohmann::ordered_json report;
  nlohmann::json seconds;
  SurfaceCheck check;
  RepairReport repair;
  ctx.progress.checkpoint(0.0, "importing " + d.design.surface.filename().string());
  const SurfaceMesh surface = prepared_surface(d, check, repair, seconds);
  for (const std::string& w : check.warnings) ctx.log.warn("surface {}: {}", surface.source.filename().string(), w);
  for (const std::string& change : repair.changes()) ctx.log.info("repair: {}", change);

  const double edge = target_edge_length(d, check.volume);
  const double estimate = require_mesh_size(d, surface, check.volume, edge, d.mesh.surface_triangles);
  ctx.log.info("surface: {} vertices, {} faces, volume {:.6g} mm³; target edge {:.4g} mm: about {:.3g} tets",
               surface.num_vertices(), surface.num_faces(), check.volume / units::mm3, edge / units::mm, estimate);
  const auto t = Clock::now();
  ctx.progress.checkpoint(0.1, "tetrahedralizing");
  const BodyMesh body = mesh_body(surface, d.mesh.surface_triangles, tet_options(d, edge), ctx.progress);
  const MeshedSurface& meshed = body.surface;
  const TetMesh& mesh = body.mesh;
  seconds["remesh and tetrahedralize"] = since(t);
  log_treatment(ctx, surface, body, edge);
  log_sizing(ctx, body, edge);
  const SurfaceFollowing following = surface_following(surface, meshed, mesh, edge);
  warn_lost_features(ctx, meshed, following, edge);
  ctx.progress.checkpoint(0.8, "measuring quality");
  const MeshQuality q = mesh_quality(mesh, d.mesh.radius_edge_ratio, d.mesh.min_dihedral_deg);
  require_sound_mesh(d, ctx, mesh, q, meshed, following);

  ctx.progress.checkpoint(0.9, "writing");
  save_tet_mesh(mesh, ctx.output_dir / "body.tetmesh");
  write_mesh_vtu(ctx.output_dir / "body.vtu", mesh);

  seconds["total"] = since(start);
  report["surface"] = {{"file", d.design.surface.string()},
                       {"units", d.design.units},
                       {"vertices", surface.num_vertices()},
                       {"faces", surface.num_faces()},
                       {"components", check.components},
                       {"volume_mm3", check.volume / units::mm3},
                       {"bounds_mm", {{"min", point_mm(check.min)}, {"max", point_mm(check.max)}}},
                       {"warnings", check.warnings},
                       {"repaired", repair.changes()}};
  report["mesh"] = {
      {"nodes", mesh.nodes.rows()},
      {"tets", mesh.num_tets()},
      {"nodes_per_tet", mesh.nodes_per_tet()},
      {"boundary_faces", mesh.boundary_faces.rows()},
      {"volume_mm3", q.volume / units::mm3},
      {"volume_mL", q.volume / units::mL},
      {"target_edge_length_mm", edge / units::mm},
      {"mean_edge_length_mm", q.mean_edge_length / units::mm},
      {"edge_length_mm",
       {{"mean", q.mean_edge_length / units::mm},
        {"min", q.min_edge_length / units::mm},
        {"max", q.max_edge_length / units::mm}}},
      {"sizing",
       {{"estimated_tets", std::round(estimate)},
        {"tetgen_runs", body.sizing.tetgen_runs},
        {"volume_bound_factor", body.sizing.volume_bound_factor},
        {"first_treatment", choice_name(body.sizing.first_treatment)},
        {"mean_edge_within_tolerance", std::abs(q.mean_edge_length / edge - 1) <= kEdgeLengthTolerance},
        {"tolerance", kEdgeLengthTolerance}}},
      {"surface_triangles", surface_triangles_report(d, surface, meshed, following)},
      {"quality_bounds_met", q.over_ratio + q.under_dihedral == 0},
      {"tets_over_radius_edge_bound", q.over_ratio},
      {"tets_under_dihedral_bound", q.under_dihedral},
      {"min_dihedral_deg", q.min_dihedral_deg},
      {"max_dihedral_deg", q.max_dihedral_deg},
      {"radius_edge_ratio",
       {{"mean", q.mean_radius_edge_ratio}, {"max", q.max_radius_edge_ratio}, {"bound", d.mesh.radius_edge_ratio}}},
      {"min_dihedral_bound_deg", d.mesh.min_dihedral_deg}};
  // Timings go to the log, not the report: an output that changes on every run would make every
  // downstream stage rerun after a rerun of this one.
  ctx.log.info("seconds: {}", seconds.dump());
  write_json_atomic(ctx.output_dir / "report.json", report);
  ctx.log.info("mesh: {} nodes, {} tets, volume {:.6g} mL, dihedral angles {:.1f}°–{:.1f}°, in {:.2f} s",
               mesh.nodes.rows(), mesh.num_tets(), q.volume / units::mL, q.min_dihedral_deg, q.max_dihedral_deg,
               since(start));
}

} // namespace fibermold
