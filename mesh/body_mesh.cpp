#include "mesh/body_mesh.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/input_error.hpp"
#include "core/units.hpp"
#include "mesh/mesh_quality.hpp"
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
  throw InputError(std::vector<Diagnostic>{
      {input.source, 0, 0, "",
       fmt::format("remeshed at {:.4g} mm edges, surface {} {} near {}: its features are thinner than the edge length "
                   "there; give a smaller [mesh] edge_length, or surface_triangles = \"split\" (or \"keep\") "
                   "to mesh the input's own triangles",
                   edge_length / units::mm, input.source.filename().string(), p.message, format_mm(p.where))}});
}

/// How far a mean edge is from the edge length asked, as a factor either way (1.2 for 20 % off).
double size_miss(double mean_edge, double edge_length) { return std::exp(std::abs(std::log(mean_edge / edge_length))); }

bool within_tolerance(double mean_edge, double edge_length)
{
  return std::abs(mean_edge / edge_length - 1) <= kEdgeLengthTolerance;
}

/// TetGen on `meshed` (its triangles kept unless split), its volume bound rescaled when the mean
/// edge misses the edge length by more than kEdgeLengthTolerance (split: kEdgeLengthAim), then
/// until it is within kEdgeLengthAim; with the surface's triangles kept, only to refine a mesh
/// coarser than asked. TetGen's bound caps each tet's volume: tets come out smaller than the
/// bound's regular tet, the more so where TetGen splits the surface's triangles for its quality
/// bound (a 12-triangle 100 × 15 × 15 mm box at 3 mm: a mean edge of 2.22 mm at the bound of a 3 mm
/// tet, 2.85 mm at twice it). The mean edge grows about as the bound's cube root, so the first
/// correction scales the bound by (asked / made)³; later ones follow the slope of log(mean edge)
/// over log(bound) the runs measured (a secant), since features narrower than the edge length hold
/// it back (the gripper finger's slots: 0.89 × asked at 3× the bound, 0.90 at 4×, 1.20 at 6×).
TetMesh sized_mesh(const MeshedSurface& meshed, TetOptions options, Progress& progress, MeshSizing& sizing)
{
  constexpr int kMaxRuns = 5;
  constexpr double kLargestFactor = 64; // a tet 4× the edge asked: beyond, the surface holds the size, not the bound
  options.keep_surface = meshed.treatment != SurfaceTriangles::split;
  const double edge = options.edge_length;
  TetMesh best;
  double last_log_factor = 0, last_log_mean = 0;
  for (int run = 0; run < kMaxRuns; ++run) {
    TetMesh mesh = tetrahedralize(meshed.surface, options, progress);
    ++sizing.tetgen_runs;
    const double mean = mean_edge_length(mesh);
    if (run == 0 || size_miss(mean, edge) < size_miss(sizing.mean_edge_length, edge)) {
      best = std::move(mesh);
      sizing.mean_edge_length = mean;
      sizing.volume_bound_factor = options.volume_bound_factor;
    }
    // Split, the bound is the mesh's only size: brought within kEdgeLengthAim from the first run.
    const double miss = std::abs(mean / edge - 1);
    if (miss <= (run == 0 && options.keep_surface ? kEdgeLengthTolerance : kEdgeLengthAim)) break;
    // Triangles TetGen must keep hold the boundary at their size: a larger bound would only grade
    // the interior coarse behind a fine skin. Too fine, such a mesh is the surface's doing.
    if (options.keep_surface && mean < edge) break;
    const double log_factor = std::log(options.volume_bound_factor), log_mean = std::log(mean);
    double slope = 1.0 / 3; // mean edge ∝ bound^(1/3)
    if (run > 0 && log_factor != last_log_factor)
      slope = std::clamp((log_mean - last_log_mean) / (log_factor - last_log_factor), 1.0 / 6, 1.0);
    last_log_factor = log_factor;
    last_log_mean = log_mean;
    const double next = std::exp(log_factor + std::log(edge / mean) / slope);
    options.volume_bound_factor = std::clamp(next, 1 / kLargestFactor, kLargestFactor);
    if (std::log(options.volume_bound_factor) == log_factor) break; // held at the clamp
  }
  return best;
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

double expected_tets(double volume, double edge_length, SurfaceTriangles policy, const SurfaceMesh& surface)
{
  SurfaceTriangles treatment = surface_treatment(policy, surface, edge_length);
  double rho = 1; // split: the volume bound is brought to the edge length
  if (treatment == SurfaceTriangles::keep) {
    const double mean_area =
        surface_area(surface) / static_cast<double>(std::max<Eigen::Index>(surface.num_faces(), 1));
    rho = std::sqrt(std::sqrt(4 * mean_area / std::sqrt(3.0)) / edge_length);
    if (rho > 1 + kEdgeLengthTolerance) rho = 1; // mesh_body tightens the volume bound to bring it there
    // Finer, the kept triangles hold the mesh; at "auto" mesh_body remeshes them instead.
    if (rho < 1 - kEdgeLengthTolerance && policy == SurfaceTriangles::automatic) treatment = SurfaceTriangles::remesh;
  }
  if (treatment == SurfaceTriangles::remesh) rho = std::sqrt(kRemeshedMeanEdge);
  const double k = treatment == SurfaceTriangles::split ? 1.25 : 1.45;
  return k * volume / regular_tet_volume(rho * edge_length);
}

BodyMesh mesh_body(const SurfaceMesh& input, SurfaceTriangles policy, const TetOptions& options, Progress& progress)
{
  BodyMesh body;
  body.surface = surface_for_mesh(input, policy, options.edge_length);
  body.sizing.first_treatment = body.surface.treatment;
  body.mesh = sized_mesh(body.surface, options, progress, body.sizing);
  if (policy == SurfaceTriangles::automatic && body.surface.treatment != SurfaceTriangles::remesh &&
      !within_tolerance(body.sizing.mean_edge_length, options.edge_length)) {
    // The surface's own vertices hold the mesh off the edge length (close input vertices make
    // TetGen's quality bound refine around them): the surface remeshed to it, when that is valid
    // and comes closer.
    try {
      MeshSizing sizing;
      sizing.first_treatment = body.sizing.first_treatment;
      sizing.tetgen_runs = body.sizing.tetgen_runs;
      MeshedSurface remeshed = surface_for_mesh(input, SurfaceTriangles::remesh, options.edge_length);
      TetMesh mesh = sized_mesh(remeshed, options, progress, sizing);
      body.sizing.tetgen_runs = sizing.tetgen_runs;
      if (size_miss(sizing.mean_edge_length, options.edge_length) <
          size_miss(body.sizing.mean_edge_length, options.edge_length))
        body = {std::move(remeshed), std::move(mesh), sizing};
    } catch (const InputError&) {
      // Features thinner than the edge length: the surface's own triangles stay.
    }
  }
  if (body.surface.treatment == SurfaceTriangles::remesh) attach_to_surface(body.mesh, input);
  return body;
}

} // namespace fibermold
