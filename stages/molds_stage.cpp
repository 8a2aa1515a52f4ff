#include "stages/molds_stage.hpp"

#include <cmath>

#include <Eigen/Geometry>
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

#include "core/input_error.hpp"
#include "core/json_file.hpp"
#include "core/units.hpp"
#include "export/stl_writer.hpp"
#include "mesh/surface_distance.hpp"
#include "mesh/tet_mesh.hpp"
#include "molds/grid_budget.hpp"
#include "molds/mold_block.hpp"
#include "molds/part_checks.hpp"
#include "molds/two_shot_molds.hpp"
#include "sim/hermite_spline.hpp"
#include "stages/design_simulation.hpp"
#include "stages/fibers_file.hpp"
#include "stages/routing_evaluation.hpp"
#include "stages/skin_distance.hpp"

namespace fibermold {

namespace {

using Json = nlohmann::ordered_json;

[[noreturn]] void bad(const Design& d, const std::string& key, const std::string& message)
{
  throw InputError(design_problem(d, key, message));
}

/// The body's skin the molds are made of: the input surface where the mesh remeshed it (the molds
/// keep the shape as given, not its remeshing at the edge length), else the tet mesh's boundary with
/// only the vertices it uses (the input's own triangles, or them split on their planes).
SurfaceMesh body_surface(const TetMesh& mesh)
{
  SurfaceMesh s;
  if (mesh.surface_vertices.rows() > 0) {
    s.vertices = mesh.surface_vertices;
    s.faces = mesh.surface_faces;
    return s;
  }
  Eigen::VectorXi index = Eigen::VectorXi::Constant(mesh.nodes.rows(), -1);
  int used = 0;
  for (Eigen::Index f = 0; f < mesh.boundary_faces.rows(); ++f)
    for (int c = 0; c < 3; ++c)
      if (index(mesh.boundary_faces(f, c)) < 0) index(mesh.boundary_faces(f, c)) = used++;
  s.vertices.resize(used, 3);
  for (Eigen::Index i = 0; i < mesh.nodes.rows(); ++i)
    if (index(i) >= 0) s.vertices.row(index(i)) = mesh.nodes.row(i);
  s.faces.resize(mesh.boundary_faces.rows(), 3);
  for (Eigen::Index f = 0; f < mesh.boundary_faces.rows(); ++f)
    for (int c = 0; c < 3; ++c) s.faces(f, c) = index(mesh.boundary_faces(f, c));
  return s;
}

/// A route as the molds see it: its spline sampled about every `step` along its length.
MoldFiber mold_fiber(const Route& r, double step)
{
  const HermiteSpline s(r.points, r.tangents);
  const int n = std::max(2, static_cast<int>(std::ceil(s.length() / step)));
  MoldFiber f;
  f.name = r.name;
  f.start = r.points.front();
  f.end = r.points.back();
  f.start_tangent = r.tangents.front();
  f.end_tangent = r.tangents.back();
  f.length = s.length();
  for (double v : segment_parameters(s, n)) f.line.push_back(s.position(v));
  return f;
}

/// Per route, the stretches at its ends on the skin that the molds' checks leave out: where the
/// optimizer's skin barrier did not hold it (skin_held, set by the routes the optimizer started
/// from), as arcs along the route as collide left it; collide tests the skin over the same stretch.
std::vector<ExitStretches> exit_stretches(const Design& d, const SurfaceDistance& skin,
                                          const std::vector<Route>& routes)
{
  const std::vector<HeldStretch> held = skin_held(d, skin, optimization_start(d, skin).routing.routes);
  std::vector<ExitStretches> out;
  for (std::size_t f = 0; f < routes.size(); ++f) {
    const HermiteSpline s(routes[f].points, routes[f].tangents);
    if (held[f].first > held[f].last)
      out.push_back({s.length(), s.length()}); // held nowhere: a short fiber between two ends on the skin
    else
      out.push_back({s.length(0, held[f].first), s.length(held[f].last, s.spans())});
  }
  return out;
}

/// A reported quantity to six decimals (mL: a nanolitre): the digits below vary with the number of
/// threads that summed it (OpenVDB's level set volume), and the same design should give the same report.
double six_places(double v) { return std::round(v * 1e6) / 1e6; }

Json vec_mm(const Eigen::Vector3d& v) { return {v.x() / units::mm, v.y() / units::mm, v.z() / units::mm}; }

/// A fill simulation's findings for the report. No timings: the same design gives the same report.
Json fill_report(const FillPlan& plan, double voxel, const TwoShotMolds& molds)
{
  const FillResult& f = plan.fill;
  const double mm3 = units::mm3, g3 = std::pow(molds.grow, 3);
  Json pockets = Json::array(), sprues = Json::array(), vents = Json::array();
  for (std::size_t k = 0; k < f.pockets.size() && k < 10; ++k)
    pockets.push_back({{"volume_mm3", six_places(g3 * f.pockets[k].volume / mm3)},
                       {"top_mm", vec_mm(molds.scaled(f.pockets[k].at))},
                       {"ventable", f.pockets[k].ventable}});
  for (std::size_t k = 0; k < plan.ports.sprues.size(); ++k)
    sprues.push_back({{"mouth_mm", vec_mm(molds.scaled(plan.ports.sprues[k].mouth))},
                      {"from", plan.ports.sprues[k].upward ? "above" : "below"},
                      {"opens_on_fill_region", static_cast<bool>(f.sprue_open[k])}});
  for (std::size_t k = 0; k < plan.ports.vents.size(); ++k)
    vents.push_back({{"mouth_mm", vec_mm(molds.scaled(plan.ports.vents[k].mouth))},
                     {"opens_on_fill_region", static_cast<bool>(f.vent_open[k])}});
  return {{"voxel_mm", voxel / units::mm},
          {"fill_volume_mL", six_places(g3 * f.fill_volume / units::mL)},
          {"reachable_percent", f.fill_volume > 0 ? six_places(100 * f.reachable_volume / f.fill_volume) : 0.0},
          {"crevices_unfilled_mm3", six_places(g3 * f.crevice_volume / mm3)},
          {"crevices_air_mm3", six_places(g3 * f.crevice_air_volume / mm3)},
          {"overmolded_air_mm3", six_places(g3 * f.overmolded_air_volume / mm3)},
          {"trapped_air_mm3", six_places(g3 * f.trapped_volume / mm3)},
          {"trapped_air_tolerance_mm3", kTrappedAirTolerance / mm3},
          {"pockets", pockets},
          {"sprues", sprues},
          {"vents", vents}};
}

Json molds_report(const TwoShotMolds& molds, const Design& d)
{
  const MoldOptions& m = d.mold;
  Json shots = Json::object(), parts = Json::object();
  for (const ShotMold& s : molds.shots) {
    Json ribs = Json::array();
    for (const ThinRib& r : s.thin_ribs)
      ribs.push_back({{"half", r.upper ? "upper" : "lower"},
                      {"tip_mm", vec_mm(r.at)},
                      {"thickness_mm", six_places(r.thickness / units::mm)},
                      {"depth_mm", six_places(r.depth / units::mm)}});
    shots[s.name] = {{"cavity_volume_mL", six_places(s.cavity_volume / units::mL)},
                     {"upper_contact_within_3deg_of_pull_percent", six_places(100 * s.upright_share)},
                     {"silicone_volume_mL", six_places(s.silicone_volume / units::mL)},
                     {"silicone_mass_g", six_places(s.silicone_volume * d.material.density / units::gram)},
                     {"parting_point_mm", vec_mm(s.parting.point)},
                     {"parting_normal", {s.parting.normal.x(), s.parting.normal.y(), s.parting.normal.z()}},
                     {"undercut_area_mm2", s.parting.undercut_area / units::mm2},
                     {"sprues", s.sprues},
                     {"vents", s.vents},
                     {"keys", s.keys},
                     {"screw_holes", s.screw_holes},
                     {"thin_ribs", ribs},
                     {"fill", fill_report(s.plan, s.fill_voxel, molds)}};
  }
  for (const CheckedPart& p : molds.parts) {
    const PartCheck& c = p.check;
    Json labels = Json::array();
    for (const PlacedLabel& l : p.part.labels)
      labels.push_back({{"text", l.text},
                        {"face", l.face},
                        {"normal", {l.normal.x() + 0.0, l.normal.y() + 0.0, l.normal.z() + 0.0}},
                        {"up", {l.up.x() + 0.0, l.up.y() + 0.0, l.up.z() + 0.0}},
                        {"centre_mm", vec_mm(l.centre)},
                        {"height_mm", l.height / units::mm},
                        {"size_mm", {l.extent.x() / units::mm, l.extent.y() / units::mm}},
                        {"depth_mm", l.depth / units::mm}});
    parts[p.part.name] = {{"shot", p.shot},
                          {"file", p.part.name + ".stl"},
                          {"triangles", p.part.mesh.num_faces()},
                          {"volume_mL", six_places(c.volume / units::mL)},
                          {"size_mm", vec_mm(c.size)},
                          {"min_wall_mm", c.min_thickness / units::mm},
                          {"min_wall_at_mm", vec_mm(c.min_thickness_at)},
                          {"fits_printer", c.fits},
                          {"print_axes", {c.orientation.x(), c.orientation.y(), c.orientation.z()}},
                          {"checks_passed", c.ok()},
                          {"labels", labels},
                          {"labels_left_out", p.part.unlabelled}};
    if (!(c.min_thickness > 0)) parts[p.part.name].erase("min_wall_at_mm"); // not measured: not a solid
  }
  const SiliconeThickness& t = molds.thickness;
  // A thickness nothing measured is "none", and has no place.
  Json silicone = Json::object();
  const auto thinnest = [&](const char* key, double v, const Eigen::Vector3d& at) {
    silicone[fmt::format("{}_mm", key)] = std::isfinite(v) ? Json(v / units::mm) : Json("none");
    if (std::isfinite(v)) silicone[fmt::format("{}_at_mm", key)] = vec_mm(molds.scaled(at));
  };
  thinnest("groove_wall", t.groove_web, t.groove_web_at);
  thinnest("over_muscle", t.overmold, t.overmold_at);
  silicone["min_silicone_mm"] = m.min_silicone / units::mm;
  const GrooveBody& g = molds.groove;
  return {{"voxel_mm", m.voxel / units::mm},
          {"groove_radius_mm", molds.groove_radius / units::mm},
          {"groove_mesh_volume_error", six_places(std::abs(signed_volume(g.mesh) - g.volume) / g.volume)},
          {"shrink", m.shrink},
          {"draft_deg", m.draft_deg},
          {"draft_offset_mm", molds.draft_offset / units::mm},
          {"silicone_thickness", silicone},
          {"shots", shots},
          {"parts", parts}};
}

} // namespace

void require_mold_grids(const Design& d, const SurfaceMesh& body,
                        const std::vector<std::vector<Eigen::Vector3d>>& fibers)
{
  const double radius = groove_radius(d.muscle.model.diameter, d.mold);
  if (const auto problem = grid_budget_problem(estimate_grids(body, d.mold.voxel, radius, fibers), d.mold.voxel))
    bad(d, "[mold].voxel", *problem);
}

void require_molds_fit_printer(const Design& d, const SurfaceMesh& body)
{
  MoldBlockOptions block = d.mold.block;
  block.min_wall = d.export_.min_wall; // as two_shot_molds gives make_mold
  SurfaceMesh cavity = body;
  cavity.vertices *= d.mold.shrink_growth(); // its size (about any centre)
  const Eigen::Vector3d half = least_half_size(cavity, d.mold.pull, block);
  if (printer_orientation(half, d.export_.printer_volume)) return;
  const Eigen::Vector3d size = body.vertices.colwise().maxCoeff() - body.vertices.colwise().minCoeff();
  bad(d, "[export].printer_volume",
      fmt::format("the molds' larger half will be at least {} (the block around the body, {} in the design's "
                  "frame, grown by [mold] wall and the rim the keys take, half its height along [mold] pull), "
                  "which fits the printer's {} in none of the 6 orientations: check [design].units, scale the "
                  "body down, or give the printer_volume of a larger printer",
                  format_size_mm(half), format_size_mm(size), format_size_mm(d.export_.printer_volume)));
}

std::vector<std::vector<Eigen::Vector3d>> require_grooves_fit(const Design& d, const SurfaceDistance& skin,
                                                              const std::vector<Route>& routes,
                                                              const std::vector<ExitStretches>& exits)
{
  // The groove's need, as optimize and collide keep it (they keep the fiber at least that far in).
  const SkinDistance rule = skin_distance(d);
  std::vector<std::vector<Eigen::Vector3d>> lines;
  for (std::size_t f = 0; f < routes.size(); ++f) {
    lines.push_back(mold_fiber(routes[f], mold_line_step(d.mold)).line);
    if (auto problem = groove_problem(lines.back(), skin, rule.groove, rule.groove_terms, d.mold.pull, exits[f]))
      bad(d, fmt::format("[fiber.{}]", routes[f].name), *problem);
  }
  return lines;
}

namespace {

/// With an "auto" parting plane, the sense of [mold] pull the molds are made for: its reverse when the
/// given one leaves a half of shot 1 a plate and the reverse does not (choose_pull_sense), and every
/// groove fits opening that way; both senses logged and into `senses` for the report.
Eigen::Vector3d pull_sense(const StageContext& ctx, const MoldJob& job,
                           const std::vector<std::vector<Eigen::Vector3d>>& lines, const SurfaceDistance& skin,
                           Json& senses)
{
  const Design& d = ctx.design;
  const Eigen::Vector3d given = d.mold.pull.normalized();
  const std::vector<PullSense> both =
      choose_pull_sense(job.body, lines, groove_radius(job.muscle_diameter, d.mold), given, kUndercutWarning);
  for (const PullSense& p : both) {
    ctx.log.info("shot 1 with pull ({:.3g}, {:.3g}, {:.3g}): the plane under the grooves through {}; the shallower "
                 "half {:.2f} mm of the cavity, {:.1f} mm² of undercut",
                 p.pull.x() + 0.0, p.pull.y() + 0.0, p.pull.z() + 0.0, format_mm(p.parting.point),
                 p.thinner_half / units::mm, std::max(0.0, p.parting.undercut_area / units::mm2));
    senses.push_back({{"pull", {p.pull.x() + 0.0, p.pull.y() + 0.0, p.pull.z() + 0.0}},
                      {"parting_point_mm", vec_mm(p.parting.point)},
                      {"shallower_half_mm", p.thinner_half / units::mm},
                      {"undercut_area_mm2", std::max(0.0, p.parting.undercut_area / units::mm2)}});
  }
  const PullSense& chosen = both.front();
  if (chosen.pull.dot(given) > 0) return given;
  const SkinDistance rule = skin_distance(d);
  for (std::size_t f = 0; f < lines.size(); ++f)
    if (auto problem = groove_problem(lines[f], skin, rule.groove, rule.groove_terms, chosen.pull, job.exits[f])) {
      ctx.log.info("the pull stays as given: reversed, the groove of fiber {} would not fit: {}", d.fibers[f].name,
                   *problem);
      return given;
    }
  ctx.log.warn(
      "the pull is reversed to ({:.3g}, {:.3g}, {:.3g}): with [mold] pull as given, shot 1's plane has to pass "
      "under the grooves and leaves a half {:.2f} mm of the cavity (a plate); reversed, {:.2f} mm. Give "
      "[mold] parting to keep the pull as given",
      chosen.pull.x() + 0.0, chosen.pull.y() + 0.0, chosen.pull.z() + 0.0, both.back().thinner_half / units::mm,
      chosen.thinner_half / units::mm);
  return chosen.pull;
}

} // namespace

void MoldsStage::run(StageContext& ctx) const
{
  const Design& d = ctx.design;
  const MoldOptions& m = d.mold;
  if (m.parting && m.parting->normal.normalized().cross(m.pull.normalized()).norm() > 1e-6)
    bad(d, "[mold].parting",
        "the parting plane's normal must be parallel to [mold].pull: the halves come apart along pull");

  MoldJob job;
  job.name = d.design.name;
  const TetMesh mesh = load_tet_mesh(ctx.upstream("mesh", "body.tetmesh"));
  job.body = body_surface(mesh);
  job.muscle_diameter = d.muscle.model.diameter;
  job.min_wall = d.export_.min_wall;
  job.printer_volume = d.export_.printer_volume;
  // The route rule against the skin optimize and collide kept it from: the mesh's (remeshed, when
  // it is; the cast's own silicone, on the body as given, is the thickness check's).
  const SurfaceDistance skin(mesh.nodes, mesh.boundary_faces);
  const std::vector<Route> routes = read_fibers_json(ctx.upstream("collide", "fibers.json")).routing.routes;
  if (routes.size() != d.fibers.size())
    throw std::runtime_error(fmt::format("collide/fibers.json has {} fibers, the design {}: run collide again",
                                         routes.size(), d.fibers.size()));
  require_bend_radius(d, routes, "the route as collide left it", false);
  for (const Route& r : routes) job.fibers.push_back(mold_fiber(r, mold_line_step(m)));
  job.exits = exit_stretches(d, skin, routes);
  const std::vector<std::vector<Eigen::Vector3d>> lines = require_grooves_fit(d, skin, routes, job.exits);
  require_mold_grids(d, job.body, lines);
  require_molds_fit_printer(d, job.body);
  MoldOptions made = m;
  Json senses = Json::array();
  if (!m.parting) made.pull = pull_sense(ctx, job, lines, skin, senses);

  const MoldLog log{[&](const std::string& s) { ctx.log.info("{}", s); },
                    [&](const std::string& s) { ctx.log.warn("{}", s); }};
  const TwoShotMolds molds = two_shot_molds(job, made, ctx.progress, log);
  if (!molds.failures.empty()) {
    std::string list;
    for (const auto& f : molds.failures) list += "\n  " + f;
    throw std::runtime_error(fmt::format("the mold parts failed their checks; no part written:{}", list));
  }
  for (const CheckedPart& p : molds.parts)
    write_stl(ctx.output_dir / (p.part.name + ".stl"), p.part.mesh, "fibermold " + p.part.name + " (mm)");
  write_stl(ctx.output_dir / "groove-body.stl", molds.groove.mesh, "fibermold groove body, shot 1 (mm)");
  Json report = molds_report(molds, d);
  report["pull"] = {molds.pull.x() + 0.0, molds.pull.y() + 0.0, molds.pull.z() + 0.0}; // + 0.0: no −0
  if (!senses.empty()) report["pull_senses"] = senses;
  write_json_atomic(ctx.output_dir / "report.json", report);
}

} // namespace fibermold
