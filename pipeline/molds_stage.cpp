#include "pipeline/molds_stage.hpp"

#include <chrono>
#include <cmath>
#include <functional>
#include <optional>

#include <Eigen/Geometry>
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

#include "core/atomic_file.hpp"
#include "core/input_error.hpp"
#include "core/json_file.hpp"
#include "core/units.hpp"
#include "export/stl_writer.hpp"
#include "mesh/surface_distance.hpp"
#include "mesh/tet_mesh.hpp"
#include "molds/grid_budget.hpp"
#include "molds/groove.hpp"
#include "molds/mold_block.hpp"
#include "molds/part_checks.hpp"
#include "molds/silicone_thickness.hpp"
#include "pipeline/design_simulation.hpp"
#include "pipeline/fibers_file.hpp"

namespace fibermold {

namespace fs = std::filesystem;

namespace {

using Json = nlohmann::ordered_json;

[[noreturn]] void bad(const Design& d, const std::string& key, const std::string& message)
{
  throw InputError(design_problem(d, key, message));
}

/// The body's skin: the tet mesh's boundary with only the vertices it uses.
SurfaceMesh body_surface(const TetMesh& mesh)
{
  SurfaceMesh s;
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

/// The spline sampled about every `step` along its length.
std::vector<Eigen::Vector3d> polyline(const Route& r, double step)
{
  const HermiteSpline s(r.points, r.tangents);
  const int n = std::max(2, static_cast<int>(std::ceil(s.length() / step)));
  const std::vector<double> t = segment_parameters(s, n);
  std::vector<Eigen::Vector3d> out;
  for (double v : t) out.push_back(s.position(v));
  return out;
}

/// The stretch of a fiber at an end on the skin that the molds' checks leave out: the optimizer's
/// skin barrier's, 2 (d_min + w) (skin_barrier.cpp).
double skin_end_stretch(const Design& d) { return 2 * (d.muscle.model.diameter + d.collide.clearance); }

/// A fiber must stay in the body, and its groove away from the skin (other than above it, where
/// the groove opens) by half the [collide] clearance, so that the groove neither breaks through the
/// skin nor leaves a skin too thin to cast. The optimizer keeps a whole clearance around the muscle
/// at its samples; half of it leaves room between them. Near an end on the skin, where the fiber
/// leaves the body by design, the same stretch as the optimizer's skin barrier is exempt.
void check_fiber(const Design& d, const Route& r, const std::vector<Eigen::Vector3d>& line, const SurfaceDistance& skin,
                 double radius, const Eigen::Vector3d& pull)
{
  const std::string key = fmt::format("[fiber.{}]", r.name);
  const double need = radius + d.collide.clearance / 2;
  const std::vector<bool> beyond = beyond_skin_ends(line, skin, skin_end_stretch(d));
  for (std::size_t k = 0; k < line.size(); ++k) {
    const Eigen::Vector3d& p = line[k];
    const auto at = skin.closest(p);
    const bool near_end = !beyond[k];
    if (!at.inside && !near_end)
      bad(d, key, fmt::format("the fiber (as routed in fibers.json) leaves the body at {}", format_mm(p)));
    if (near_end) continue;
    const Eigen::Vector3d to_skin = at.point - p;
    if (at.distance < need && to_skin.dot(pull) < 0.7 * at.distance)
      bad(d, key, fmt::format("the fiber passes {:.2f} mm from the skin at {}: its groove (radius {:.2f} mm) needs {:.2f} mm "
                              "(the groove's radius + half the [collide] clearance)",
                              at.distance / units::mm, format_mm(p), radius / units::mm, need / units::mm));
  }
}

SurfaceMesh scaled_about(SurfaceMesh m, const Eigen::Vector3d& centre, double factor)
{
  m.vertices = ((m.vertices.rowwise() - centre.transpose()) * factor).rowwise() + centre.transpose();
  return m;
}

/// An undercut below this projected area (m²) is facets of the meshed level set, not a shape the
/// mold holds on to: it is reported but not warned about.
constexpr double kUndercutWarning = 1e-6;

/// A reported quantity to six decimals (mL: a nanolitre): the digits below vary with the number of
/// threads that summed it (OpenVDB's level set volume), and the same design should give the same report.
double six_places(double v) { return std::round(v * 1e6) / 1e6; }

Json vec_mm(const Eigen::Vector3d& v) { return {v.x() / units::mm, v.y() / units::mm, v.z() / units::mm}; }

/// A fill simulation's findings for the report, and its failures: a part no sprue reaches, or
/// trapped air beyond the tolerance, each named by where it is. `scale` maps a point to the
/// shrink-scaled cavity, `g3` a volume. No timings: the same design gives the same report.
Json fill_report(const FillPlan& plan, double voxel, const std::function<Eigen::Vector3d(const Eigen::Vector3d&)>& scale, double g3,
                 const std::string& shot, std::vector<std::string>& problems)
{
  const FillResult& f = plan.fill;
  const double mm3 = 1e-9;
  Json pockets = Json::array(), sprues = Json::array(), vents = Json::array();
  for (std::size_t k = 0; k < f.pockets.size() && k < 10; ++k)
    pockets.push_back({{"volume_mm3", six_places(g3 * f.pockets[k].volume / mm3)},
                       {"top_mm", vec_mm(scale(f.pockets[k].at))},
                       {"ventable", f.pockets[k].ventable}});
  for (std::size_t k = 0; k < plan.ports.sprues.size(); ++k)
    sprues.push_back({{"mouth_mm", vec_mm(scale(plan.ports.sprues[k].mouth))},
                      {"from", plan.ports.sprues[k].upward ? "above" : "below"},
                      {"opens_on_fill_region", static_cast<bool>(f.sprue_open[k])}});
  for (std::size_t k = 0; k < plan.ports.vents.size(); ++k)
    vents.push_back({{"mouth_mm", vec_mm(scale(plan.ports.vents[k].mouth))}, {"opens_on_fill_region", static_cast<bool>(f.vent_open[k])}});
  const double unreached = f.fill_volume - f.reachable_volume - f.crevice_volume;
  if (g3 * unreached > kTrappedAirTolerance && !f.unreachable.empty())
    problems.push_back(fmt::format("{}: {:.1f} mm³ of the {:.1f} mm³ that the shot fills is reached by no sprue (the largest part, "
                                   "{:.1f} mm³, lowest at {}) with {} sprue(s) placed: no other fits near it",
                                   shot, g3 * unreached / mm3, g3 * f.fill_volume / mm3, g3 * f.unreachable.front().volume / mm3,
                                   format_mm(scale(f.unreachable.front().at)), plan.ports.sprues.size()));
  if (g3 * f.trapped_volume > kTrappedAirTolerance && !f.pockets.empty()) {
    const AirPocket& worst = f.pockets.front();
    problems.push_back(fmt::format("{}: the rising silicone traps {:.1f} mm³ of air, allowed {:.1f} mm³: the largest pocket, {:.1f} mm³, "
                                   "tops out at {} {}",
                                   shot, g3 * f.trapped_volume / mm3, kTrappedAirTolerance / mm3, g3 * worst.volume / mm3,
                                   format_mm(scale(worst.at)),
                                   worst.ventable ? fmt::format("with {} vents placed: no more fits near it (within 3 mm the skin slopes more than 35°, or "
                                                               "another vent let out no more air)",
                                                               plan.ports.vents.size())
                                                  : std::string("under cured silicone, a muscle or an overhang of the body, where no "
                                                                "vent can reach it; another [mold] pull may open it upward")));
  }
  return {{"voxel_mm", voxel / units::mm},
          {"fill_volume_mL", six_places(g3 * f.fill_volume / 1e-6)},
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

} // namespace

void require_mold_grids(const Design& d, const SurfaceMesh& body, const std::vector<std::vector<Eigen::Vector3d>>& fibers)
{
  const double radius = d.muscle.model.diameter / 2 + d.mold.groove_clearance;
  if (const auto problem = grid_budget_problem(estimate_grids(body, d.mold.voxel, radius, fibers), d.mold.voxel))
    bad(d, "[mold].voxel", *problem);
}

void MoldsStage::run(StageContext& ctx) const
{
  const Design& d = ctx.design;
  const MoldOptions& m = d.mold;

  const TetMesh mesh = load_tet_mesh(ctx.upstream("mesh", "body.tetmesh"));
  const SurfaceMesh body = body_surface(mesh);
  const SurfaceDistance skin(body.vertices, body.faces);
  const FibersFile fibers = read_fibers_json(ctx.upstream("collide", "fibers.json"));
  const double radius = d.muscle.model.diameter / 2 + m.groove_clearance;
  const Eigen::Vector3d pull = m.pull.normalized();
  if (m.parting && m.parting->normal.normalized().cross(pull).norm() > 1e-6)
    bad(d, "[mold].parting", "the parting plane's normal must be parallel to [mold].pull: the halves come apart along pull");

  std::vector<std::vector<Eigen::Vector3d>> lines;
  std::vector<Channel> channels;
  double muscle_volume = 0;
  for (const Route& r : fibers.routing.routes) {
    lines.push_back(polyline(r, std::min(0.5e-3, m.voxel * 2)));
    check_fiber(d, r, lines.back(), skin, radius, pull);
    muscle_volume += HermiteSpline(r.points, r.tangents).length() * M_PI * std::pow(d.muscle.model.diameter / 2, 2);
    // An end on the skin gets a channel out through the mold, square to the skin there (a channel
    // meeting the skin at an angle would leave a knife edge of mold): from a point 1 mm inside, back
    // along the fiber, to its nearest skin point. Where the fiber leaves the skin almost along it
    // (that point is not inside: the walking robot's bend fiber once left its end face 81° off
    // the face's normal, and its channel, laid along the fiber, cut the body diagonally and left a
    // 0.08 mm wall), the deepest of the points 1 mm in along ±x, ±y, ±z serves instead.
    const auto add_channel = [&](const Eigen::Vector3d& end, const Eigen::Vector3d& along) {
      if (skin.closest(end).distance >= radius) return;  // the fiber ends inside the body
      const auto square_out = [&](const Eigen::Vector3d& in, double& depth) -> std::optional<Eigen::Vector3d> {
        const Eigen::Vector3d inside = end + 1e-3 * in;
        const auto at = skin.closest(inside);
        depth = at.distance;
        if (!(at.inside && at.distance > 1e-6)) return std::nullopt;
        return Eigen::Vector3d((at.point - inside).normalized());
      };
      double depth = 0, deepest = 0;
      std::optional<Eigen::Vector3d> out = square_out(-along.normalized(), depth), best;
      for (int axis = 0; !out && axis < 6; ++axis) {
        const Eigen::Vector3d in = (axis % 2 ? -1.0 : 1.0) * Eigen::Vector3d::Unit(axis / 2);
        if (const auto o = square_out(in, depth); o && depth > deepest) best = o, deepest = depth;
      }
      const Eigen::Vector3d dir = out ? *out : best.value_or(along.normalized());
      channels.push_back({end - 1e-3 * dir, dir, m.end_channel_diameter, 1e-3 + m.end_channel_length, d.muscle.model.diameter});
    };
    add_channel(r.points.front(), -r.tangents.front());
    add_channel(r.points.back(), r.tangents.back());
  }

  require_mold_grids(d, body, lines);

  ctx.progress.checkpoint(0.1, "carving the grooves (level set)");
  using Clock = std::chrono::steady_clock;
  const auto since = [](Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); };
  auto started = Clock::now();
  GrooveBody groove = groove_body(body, lines, radius, pull, m.voxel);
  const auto log_groove = [&] {
    ctx.log.info("groove body: {} triangles (adaptivity {}), {:.2f} mL (meshed {:.2f} mL), voxel {:.2f} mm, in {:.2f} s",
                 groove.mesh.num_faces(), groove.adaptivity, groove.volume / 1e-6, signed_volume(groove.mesh) / 1e-6,
                 m.voxel / units::mm, since(started));
  };
  log_groove();

  MoldBlockOptions o;
  o.wall = m.wall;
  o.min_wall = d.export_.min_wall;
  o.keys = m.keys;
  o.key_shape = m.key_shape;
  o.key_diameter = m.key_diameter;
  o.key_clearance = m.key_clearance;
  o.sprue_diameter = m.sprue_diameter;
  o.vents = m.vents;
  o.vent_diameter = m.vent_diameter;
  o.screw_holes = m.screw_holes;
  o.screw_diameter = m.screw_diameter;
  // Shrink compensation: cavities (and channel starts) scaled up about the body's centre.
  const double grow = m.shrink > 0 ? 1 / (1 - m.shrink) : 1.0;
  const Eigen::Vector3d centre = body.vertices.colwise().mean().transpose();
  for (Channel& c : channels) c.start = centre + (c.start - centre) * grow;
  const double body_volume = signed_volume(body), g3 = grow * grow * grow;
  // The silicone that fills each channel's socket around the muscle's end.
  const double sleeves = static_cast<double>(channels.size()) * M_PI *
                         (std::pow(m.end_channel_diameter / 2, 2) - std::pow(std::min(m.end_channel_diameter, d.muscle.model.diameter) / 2, 2)) *
                         m.end_channel_length;

  Json shots = Json::object(), parts = Json::object();
  std::vector<std::string> failures;
  std::vector<MoldPart> all;
  // One shot's mold: its parts checked; the problems found, one line each. Parts too big for the
  // printer are also listed apart: meshing the cavity again cannot help them.
  std::vector<std::string> too_big;
  std::optional<Draft> draft;
  // What each shot fills, sampled for the fill simulation (once: both shots' from the body, drafted or not).
  FillRegions regions;
  const auto scale = [&](const Eigen::Vector3d& p) -> Eigen::Vector3d { return centre + (p - centre) * grow; };
  // A shot's fill problems apart from its parts': meshing the cavity again cannot help them.
  std::vector<std::string> fill_failures;
  // Shot 1 fills the grooved body from below; shot 2 the grooves around the laid muscles, over
  // cured silicone: its sprues come from above (ports.hpp).
  const auto make_shot = [&](const char* name, const SurfaceMesh& shot_cavity, Parting parting, double silicone,
                             const std::vector<Channel>& shot_channels) {
    std::vector<std::string> problems;
    const bool first = name == std::string("shot1");
    ctx.progress.checkpoint(first ? 0.25 : 0.55, fmt::format("{}: fill simulation", name));
    started = Clock::now();
    const VoxelRegion& region = first ? regions.shot1 : regions.shot2;
    FillPlan plan = plan_fill(region, shot_cavity,
                              first ? cavity_ports(shot_cavity, pull, o.sprue_diameter, o.vents, o.vent_diameter, o.min_wall, name) : Ports{},
                              o.sprue_diameter, o.vent_diameter, !first, first ? &regions.shot2 : nullptr, kTrappedAirTolerance / g3);
    const double fill_seconds = since(started);
    std::erase_if(fill_failures, [&](const std::string& f) { return f.starts_with(name); });  // a shot made again
    const Json fill = fill_report(plan, region.voxel, scale, g3, name, fill_failures);
    for (std::size_t k = 0; k < plan.fill.pockets.size() && k < 5; ++k)
      ctx.log.info("{}: air pocket of {:.2f} mm³ topping out at {}{}", name, g3 * plan.fill.pockets[k].volume / 1e-9,
                   format_mm(scale(plan.fill.pockets[k].at)), plan.fill.pockets[k].ventable ? "" : " (under solid: no vent reaches it)");
    ctx.log.info("{}: sprues and vents placed in {:.2f} s, of which {} fill simulation(s) on {} voxels of {:.2f} mm {:.2f} s: {} sprue(s), "
                 "{} vent(s), {:.1f} % reached, {:.2f} mm³ of air trapped",
                 name, fill_seconds, plan.simulations, region.count(), region.voxel / units::mm, plan.simulation_seconds,
                 plan.ports.sprues.size(), plan.ports.vents.size(),
                 fill["reachable_percent"].get<double>(), fill["trapped_air_mm3"].get<double>());
    for (Port& p : plan.ports.sprues) p.mouth = scale(p.mouth);
    for (Port& p : plan.ports.vents) p.mouth = scale(p.mouth);
    ctx.progress.checkpoint(first ? 0.3 : 0.6, fmt::format("{}: mold block", name));
    const SurfaceMesh cavity = grow != 1 ? scaled_about(shot_cavity, centre, grow) : shot_cavity;
    parting.point = centre + (parting.point - centre) * grow;
    parting.undercut_area = undercut_area(cavity, parting.point, parting.normal);
    ctx.log.info("{}: parting plane through {} normal to pull, {:.1f} mm² of undercut", name, format_mm(parting.point),
                 parting.undercut_area / 1e-6);
    if (parting.undercut_area > kUndercutWarning)
      ctx.log.warn("{}: {:.1f} mm² of the cavity is an undercut for the parting plane: demolding relies on the silicone bending",
                   name, parting.undercut_area / 1e-6);
    started = Clock::now();
    const Mold mold = make_mold(cavity, parting, shot_channels, o, name, &plan.ports);
    ctx.log.info("{}: mold block and parts in {:.2f} s", name, since(started));
    const double upright = upright_share(cavity, parting.point, parting.normal, 3);
    ctx.log.info("{}: {:.0f} % of the upper half's contact lies within 3° of the pull (walls it slides along; draft_deg {})", name,
                 100 * upright, m.draft_deg);
    shots[name] = {{"cavity_volume_mL", six_places(signed_volume(cavity) / 1e-6)},
                   {"upper_contact_within_3deg_of_pull_percent", six_places(100 * upright)},
                   {"silicone_volume_mL", six_places(silicone / 1e-6)},
                   {"silicone_mass_g", six_places(silicone * d.material.density * 1e3)},
                   {"parting_point_mm", vec_mm(parting.point)},
                   {"parting_normal", {parting.normal.x(), parting.normal.y(), parting.normal.z()}},
                   {"undercut_area_mm2", parting.undercut_area / 1e-6},
                   {"sprues", mold.sprues.size()},
                   {"vents", mold.vents.size()},
                   {"keys", mold.keys.size()},
                   {"screw_holes", mold.screws.size()},
                   {"fill", fill}};
    if (static_cast<int>(mold.screws.size()) < m.screw_holes)
      ctx.log.warn("{}: room for {} of the {} screw holes asked for (channels and keys take the other sites in the rim)", name,
                   mold.screws.size(), m.screw_holes);
    for (const MoldPart& p : mold.parts) {
      ctx.progress.checkpoint(-1, "checking " + p.name);
      started = Clock::now();
      const PartCheck c = check_part(p.mesh, d.export_.min_wall, d.export_.printer_volume);
      ctx.log.info("{}: {} triangles, checked in {:.2f} s", p.name, p.mesh.num_faces(), since(started));
      for (const std::string& problem : c.problems) problems.push_back(fmt::format("part {} {}", p.name, problem));
      if (!c.fits) too_big.push_back(p.name);
      parts[p.name] = {{"shot", name},
                       {"file", p.name + ".stl"},
                       {"triangles", p.mesh.num_faces()},
                       {"volume_mL", six_places(c.volume / 1e-6)},
                       {"size_mm", vec_mm(c.size)},
                       {"min_wall_mm", c.min_thickness / units::mm},
                       {"fits_printer", c.fits},
                       {"print_axes", {c.orientation.x(), c.orientation.y(), c.orientation.z()}},
                       {"checks_passed", c.ok()}};
      all.push_back(p);
    }
    return problems;
  };
  // Shot 1 fills the scaled-up groove cavity; its cured part shrinks back to nominal size. The
  // adaptive mesh of the groove body can leave a facet that a part's checks reject (a sliver wall):
  // then shot 1 is made again from the uniform mesh, which they have been proven on.
  const auto user_parting = [&] { return Parting{m.parting->point, m.parting->normal.normalized(), 0}; };
  const Parting parting1 = m.parting ? user_parting() : choose_parting(groove.mesh, pull);
  Parting parting2 = m.parting ? user_parting() : choose_parting(body, pull);
  // With a draft both shots share shot 1's plane (see molds/draft.hpp), and both cavities are made again drafted.
  SurfaceMesh shot2_cavity = body;
  double shot2_volume = body_volume;
  bool shot2_adaptive = false;
  if (m.draft_deg > 0) {
    draft = draft_for(body, pull, parting1.point, m.draft_deg * M_PI / 180, m.voxel);
    parting2 = parting1;
    started = Clock::now();
    GrooveBody drafted;
    groove = groove_body(body, lines, radius, pull, m.voxel, kGrooveAdaptivity, &*draft, &drafted);
    log_groove();
    shot2_cavity = drafted.mesh;
    shot2_volume = drafted.volume;
    shot2_adaptive = drafted.adaptivity > 0;
    // The sockets reach end_channel_length beyond the drafted skin.
    for (Channel& c : channels) c.socket += draft->offset(c.start.dot(pull));
    ctx.log.info("draft {}°: cavities grown by up to {:.2f} mm at the parting plane; the body takes {:.2f} mL more silicone",
                 m.draft_deg, draft->most() / units::mm, (shot2_volume - body_volume) / 1e-6);
  }
  ctx.progress.checkpoint(0.2, "sampling what each shot fills");
  started = Clock::now();
  regions = fill_regions(shot2_cavity, lines, radius, d.muscle.model.diameter / 2, pull, fill_voxel(m.voxel, radius), draft ? draft->slope : 0);
  ctx.log.info("fill regions: {} and {} voxels of {:.2f} mm (shots 1 and 2) in {:.2f} s", regions.shot1.count(), regions.shot2.count(),
               regions.shot1.voxel / units::mm, since(started));
  failures = make_shot("shot1", groove.mesh, parting1, g3 * groove.volume, {});
  if (!failures.empty() && groove.adaptivity > 0 && too_big.empty()) {
    ctx.log.info("shot 1 from the adaptive groove body mesh failed its checks ({}); meshing the groove body uniformly", failures.front());
    all.clear();
    started = Clock::now();
    groove = groove_body(body, lines, radius, pull, m.voxel, 0, draft ? &*draft : nullptr);
    log_groove();
    failures = make_shot("shot1", groove.mesh, parting1, g3 * groove.volume, {});
  }
  const auto shot2_silicone = [&] { return std::max(0.0, g3 * shot2_volume - groove.volume - muscle_volume + sleeves); };
  std::vector<std::string> shot2 = make_shot("shot2", shot2_cavity, parting2, shot2_silicone(), channels);
  if (!shot2.empty() && shot2_adaptive && too_big.empty()) {
    ctx.log.info("shot 2 from the adaptive drafted body mesh failed its checks ({}); meshing it uniformly", shot2.front());
    std::erase_if(all, [](const MoldPart& p) { return p.name.starts_with("shot2"); });
    const GrooveBody drafted = groove_body(body, {}, radius, pull, m.voxel, 0, &*draft);
    shot2_cavity = drafted.mesh;
    shot2_volume = drafted.volume;
    shot2 = make_shot("shot2", shot2_cavity, parting2, shot2_silicone(), channels);
  }
  failures.insert(failures.end(), shot2.begin(), shot2.end());
  failures.insert(failures.end(), fill_failures.begin(), fill_failures.end());

  // The cast silicone's thinnest places at the grooves; the stretches near an end on the skin are
  // exempt as in check_fiber.
  ctx.progress.checkpoint(0.9, "measuring the silicone's thickness");
  started = Clock::now();
  const SiliconeThickness thickness =
      silicone_thickness(groove.mesh, shot2_cavity, lines, radius, d.muscle.model.diameter / 2, pull, m.voxel, skin_end_stretch(d));
  ctx.log.info("silicone: {:.2f} mm at the thinnest groove wall near {}, {:.2f} mm over the muscles at the thinnest, near {}; in {:.2f} s",
               thickness.groove_web / units::mm, format_mm(scale(thickness.groove_web_at)), thickness.overmold / units::mm,
               format_mm(scale(thickness.overmold_at)), since(started));
  if (thickness.groove_web < m.min_silicone)
    failures.push_back(fmt::format("shot1: the cast's silicone is {:.2f} mm thin between a groove and the skin near {}, below [mold] "
                                   "min_silicone = {:.2f} mm: move the fiber away from the skin there",
                                   thickness.groove_web / units::mm, format_mm(scale(thickness.groove_web_at)), m.min_silicone / units::mm));
  if (thickness.overmold < m.min_silicone)
    failures.push_back(fmt::format("shot2: the overmold is {:.2f} mm thin over a muscle near {}, below [mold] min_silicone = {:.2f} mm: "
                                   "move the fiber deeper there",
                                   thickness.overmold / units::mm, format_mm(scale(thickness.overmold_at)), m.min_silicone / units::mm));
  const auto finite_mm = [](double v) { return std::isfinite(v) ? Json(v / units::mm) : Json("none"); };
  const Json silicone{{"groove_wall_mm", finite_mm(thickness.groove_web)},
                      {"groove_wall_at_mm", vec_mm(scale(thickness.groove_web_at))},
                      {"over_muscle_mm", finite_mm(thickness.overmold)},
                      {"over_muscle_at_mm", vec_mm(scale(thickness.overmold_at))},
                      {"min_silicone_mm", m.min_silicone / units::mm}};
  const double groove_mesh_error = std::abs(signed_volume(groove.mesh) - groove.volume) / groove.volume;
  if (!failures.empty()) {
    std::string list;
    for (const auto& f : failures) list += "\n  " + f;
    throw std::runtime_error(fmt::format("{} mold part check(s) failed; no part written:{}", failures.size(), list));
  }
  for (const MoldPart& p : all) write_stl(ctx.output_dir / (p.name + ".stl"), p.mesh, "fibermold " + p.name + " (mm)");
  write_stl(ctx.output_dir / "groove-body.stl", groove.mesh, "fibermold groove body, shot 1 (mm)");
  const Json report{{"voxel_mm", m.voxel / units::mm},
                    {"groove_radius_mm", radius / units::mm},
                    {"groove_mesh_volume_error", six_places(groove_mesh_error)},
                    {"shrink", m.shrink},
                    {"draft_deg", m.draft_deg},
                    {"draft_offset_mm", draft ? draft->most() / units::mm : 0.0},
                    {"silicone_thickness", silicone},
                    {"shots", shots},
                    {"parts", parts}};
  write_json_atomic(ctx.output_dir / "report.json", report);
}

} // namespace fibermold
