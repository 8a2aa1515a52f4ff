#include "stages/export_stage.hpp"

#include <algorithm>
#include <optional>
#include <sstream>

#include <Eigen/Geometry>
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

#include "core/atomic_file.hpp"
#include "core/json_file.hpp"
#include "core/units.hpp"
#include "core/wrapped_text.hpp"
#include "export/casting_sheet.hpp"
#include "export/lay_flat.hpp"
#include "export/muscle_cut.hpp"
#include "export/report_html.hpp"
#include "export/stl_writer.hpp"
#include "export/three_mf_writer.hpp"
#include "mesh/surface_check.hpp"
#include "mesh/surface_distance.hpp"
#include "mesh/surface_import.hpp"
#include "mesh/tet_mesh.hpp"
#include "optimize/tracking_curve.hpp"
#include "sim/hermite_spline.hpp"
#include "stages/design_simulation.hpp"
#include "stages/fibers_file.hpp"

namespace fibermold {

namespace {

using Json = nlohmann::ordered_json;

// A place that moves less than this, and turns less, stays put: it is not worth comparing.
constexpr double kStaysPut_mm = 0.5, kStaysPut_deg = 5.0;

std::vector<ReportLine> fiber_lines(const FibersFile& fibers);

/// The pull the molds were made for (molds/report.json): [mold] pull, or its reverse where that left
/// a half of shot 1 a plate.
Eigen::Vector3d molds_pull(const Json& molds)
{
  return molds.contains("pull") ? Eigen::Vector3d(molds["pull"][0], molds["pull"][1], molds["pull"][2])
                                : Eigen::Vector3d::UnitZ();
}

/// Each fiber's cut: along its centre line as collide left it (10 points per mm), against the body's skin;
/// an end leaves the body within the groove's radius of the skin (molds/report.json), and the supply end
/// is the one nearest the [[fixed]] regions' centroid.
std::vector<MuscleCut> muscle_cuts(const StageContext& ctx, const TetMesh& body, const FibersFile& fibers,
                                   const Json& molds)
{
  const Design& d = ctx.design;
  const SurfaceDistance skin(body.nodes, body.boundary_faces);
  std::optional<Eigen::Vector3d> mount;
  std::vector<int> held;
  for (std::size_t i = 0; i < d.fixed.size(); ++i)
    for (int n : region_nodes(d.fixed[i].region, body, d, fmt::format("fixed[{}]", i + 1))) held.push_back(n);
  if (!held.empty()) {
    mount = Eigen::Vector3d::Zero();
    for (int n : held) *mount += body.nodes.row(n).transpose() / static_cast<double>(held.size());
  }
  const double reach = molds["groove_radius_mm"].get<double>() * units::mm;
  std::vector<MuscleCut> cuts;
  for (const ReportLine& line : fiber_lines(fibers))
    cuts.push_back(muscle_cut(line.name, line.points, skin, reach, mount));
  return cuts;
}

/// One shot of molds/report.json, for the casting sheet.
CastShot cast_shot(const Json& shot)
{
  const Json& fill = shot["fill"];
  CastShot c;
  c.volume = shot["silicone_volume_mL"].get<double>() * units::mL;
  c.mass = shot["silicone_mass_g"].get<double>() * units::gram;
  c.screw_holes = shot.value("screw_holes", 0);
  c.sprues = static_cast<int>(fill["sprues"].size());
  c.vents = static_cast<int>(fill["vents"].size());
  if (c.sprues > 0) c.sprue_from = fill["sprues"][0]["from"].get<std::string>();
  c.reached = fill["reachable_percent"].get<double>() / 100;
  c.trapped_air = fill["trapped_air_mm3"].get<double>() * units::mm3;
  c.trapped_air_tolerance = fill["trapped_air_tolerance_mm3"].get<double>() * units::mm3;
  return c;
}

/// The casting sheet of the design's molds (molds/report.json) and muscles.
CastingSheet casting_sheet(const Design& d, const Json& molds, std::vector<MuscleCut> cuts)
{
  const MaterialOptions& m = d.material;
  CastingSheet sheet;
  sheet.design_name = d.design.name;
  sheet.format = d.export_.formats.front();
  sheet.labels = d.mold.labels;
  sheet.silicone = *find_silicone_preset(m.preset.empty() ? kDefaultSilicone : m.preset);
  sheet.preset = m.preset;
  sheet.youngs_modulus = m.youngs_modulus;
  sheet.poisson_ratio = m.poisson_ratio;
  sheet.density = m.density;
  sheet.muscle_diameter = d.muscle.model.diameter;
  sheet.end_channel_diameter = d.mold.end_channel_diameter;
  sheet.cuts = std::move(cuts);
  sheet.pull = molds_pull(molds);
  sheet.shot1 = cast_shot(molds["shots"]["shot1"]);
  sheet.shot2 = cast_shot(molds["shots"]["shot2"]);
  return sheet;
}

/// Each fiber's centre line, 10 points per mm.
std::vector<ReportLine> fiber_lines(const FibersFile& fibers)
{
  std::vector<ReportLine> out;
  for (const Route& r : fibers.routing.routes) {
    const HermiteSpline spline(r.points, r.tangents);
    const int n = std::max(2, static_cast<int>(spline.length() / 0.1e-3));
    ReportLine line{r.name, {}};
    for (double t : segment_parameters(spline, n)) line.points.push_back(spline.position(t));
    out.push_back(std::move(line));
  }
  return out;
}

std::string fixed(double value, int digits) { return fmt::format("{:.{}f}", value, digits); }

/// How a part's printed pose maps back to the body's frame, in mm: printed = rotation · p + translation.
Json placement_json(const Placement& placed)
{
  Json rotation = Json::array();
  for (int i = 0; i < 3; ++i) rotation.push_back({placed.rotation(i, 0), placed.rotation(i, 1), placed.rotation(i, 2)});
  const Eigen::Vector3d t = placed.translation / units::mm;
  return {{"rotation", rotation},
          {"translation_mm", {t.x(), t.y(), t.z()}},
          {"maps", "printed = rotation · body + translation"}};
}

std::optional<Json> json_if_any(const std::filesystem::path& file)
{
  std::error_code ec;
  if (!std::filesystem::exists(file, ec)) return std::nullopt;
  Json j = Json::parse(read_file(file), nullptr, false);
  return j.is_discarded() ? std::nullopt : std::optional<Json>(std::move(j));
}

/// The body's nodes where `state` (a deformed-*.json or targets/<name>.json) puts them.
std::optional<Eigen::MatrixX3d> deformed_nodes(const TetMesh& body, const std::optional<Json>& state)
{
  if (!state || !state->contains("nodes_mm") || !(*state)["nodes_mm"].is_array() ||
      (*state)["nodes_mm"].size() != static_cast<std::size_t>(body.nodes.rows()))
    return std::nullopt;
  Eigen::MatrixX3d nodes(body.nodes.rows(), 3);
  for (Eigen::Index i = 0; i < body.nodes.rows(); ++i) {
    const Json& p = (*state)["nodes_mm"][static_cast<std::size_t>(i)];
    if (!p.is_array() || p.size() != 3) return std::nullopt;
    for (int k = 0; k < 3; ++k) {
      if (!p[static_cast<std::size_t>(k)].is_number()) return std::nullopt;
      nodes(i, k) = p[static_cast<std::size_t>(k)].get<double>() * units::mm;
    }
  }
  return nodes;
}

/// The body's skin where `state` puts its nodes.
std::optional<SurfaceMesh> deformed_body(const TetMesh& body, const std::optional<Json>& state)
{
  const std::optional<Eigen::MatrixX3d> nodes = deformed_nodes(body, state);
  if (!nodes) return std::nullopt;
  return boundary_surface(body, *nodes);
}

/// The body at rest and, per target, deformed under the final routing (collide/deformed-*.json),
/// with its fibers, at `offset`, and the target's own deformation (targets/<name>.json) beside it,
/// `beside` further; the first target's shown, the rest switched off; the tracking curves at rest.
void add_bodies(const StageContext& ctx, const TetMesh& body, const Eigen::Vector3d& offset,
                const Eigen::Vector3d& beside, std::vector<ReportMesh>& meshes, std::vector<ReportLine>& lines)
{
  bool first = true;
  for (const Target& target : ctx.design.targets) {
    const std::optional<Json> state = json_if_any(ctx.upstream("collide", "deformed-" + target.name + ".json"));
    std::optional<SurfaceMesh> deformed = deformed_body(body, state);
    if (!deformed) continue;
    meshes.push_back({"body, " + target.name, std::move(*deformed), {0.5F, 0.78F, 0.5F}, first, offset});
    if (std::optional<SurfaceMesh> asked =
            deformed_body(body, json_if_any(ctx.upstream("targets", target.name + ".json"))))
      meshes.push_back(
          {"target " + target.name + " (asked)", std::move(*asked), {0.45F, 0.6F, 0.95F}, first, offset + beside});
    for (const auto& [fiber, points] : (*state)["fibers_mm"].items()) {
      ReportLine line{target.name + ": " + fiber, {}, {0.8F, 0.1F, 0.1F}, first};
      for (const Json& p : points) line.points.push_back(offset + Eigen::Vector3d(p[0], p[1], p[2]) * units::mm);
      lines.push_back(std::move(line));
    }
    first = false;
  }
  // At rest: shown when no target's deformed state is (optimize disabled, or no targets).
  meshes.push_back({"body at rest", boundary_surface(body, body.nodes), {0.75F, 0.75F, 0.75F}, first, offset});
  for (const TrackingCurve& c : ctx.design.tracking_curves) {
    ReportLine line{"tracking curve " + c.name, {}, {0.1F, 0.3F, 0.9F}, true};
    for (const Eigen::Vector3d& p : sample_tracking_curve(c.points, std::max(c.samples, 64), 1, 0).points)
      line.points.push_back(offset + p);
    lines.push_back(std::move(line));
  }
}

/// What to compare on the cast robot for one target: where its regions and the tracking curves' ends
/// went (collide's report), leaving out the places that stay put (a curve's clamped first point).
std::string poses_to_compare(const Json& poses)
{
  std::string out;
  for (const Json& p : poses) {
    if (!p.is_object() || !p.contains("translation_mm") || !p["rotation_deg"].is_number()) continue;
    const Eigen::Vector3d t(p["translation_mm"][0], p["translation_mm"][1], p["translation_mm"][2]);
    const double turn = p["rotation_deg"].get<double>();
    if (t.norm() < kStaysPut_mm && turn < kStaysPut_deg) continue;
    // Where it is on the robot: a region's centre at rest, or the curve's point (older reports: the name only).
    const std::string where =
        p.contains("rest_mm")
            ? fmt::format(" (at {} at rest{})",
                          format_mm(Eigen::Vector3d(p["rest_mm"][0], p["rest_mm"][1], p["rest_mm"][2]) * units::mm),
                          p.contains("nodes") ? fmt::format(": the centre of its {} nodes", p["nodes"].get<int>()) : "")
            : "";
    std::string line = fmt::format(
        "{}{}: moves {:.1f} mm ({:.1f}, {:.1f}, {:.1f}) and turns {:.1f}° about ({:.2f}, {:.2f}, {:.2f})",
        p["place"].get<std::string>(), where, t.norm(), t.x(), t.y(), t.z(), turn, p["rotation_axis"][0].get<double>(),
        p["rotation_axis"][1].get<double>(), p["rotation_axis"][2].get<double>());
    if (p.contains("rotation_about_asked_axis_deg") && p.contains("asked_rotation_deg"))
      line += fmt::format("; {:.1f}° about the axis asked (asked {:.1f}°)",
                          p["rotation_about_asked_axis_deg"].get<double>(), p["asked_rotation_deg"].get<double>());
    out += wrapped(line, "    ", "      ");
  }
  return out.empty()
             ? fmt::format("    nothing moves more than {} mm or turns more than {}°\n", kStaysPut_mm, kStaysPut_deg)
             : out;
}

/// Per target, the body as simulated under the final routing (collide/deformed-<target>.json), as a
/// printable STL in the body's frame, which is the frame of the robot as mounted (its [[fixed]]
/// regions stay where they are at rest); README.txt's section on checking the cast robot with it,
/// and the files for the manifest.
std::string overlay_shapes(const StageContext& ctx, const TetMesh& body, const FibersFile& fibers, Json& files)
{
  const Design& d = ctx.design;
  const auto collide = json_if_any(ctx.upstream("collide", "report.json"));
  std::string text;
  for (std::size_t t = 0; t < d.targets.size(); ++t) {
    const std::string& name = d.targets[t].name;
    std::optional<SurfaceMesh> deformed =
        deformed_body(body, json_if_any(ctx.upstream("collide", "deformed-" + name + ".json")));
    if (!deformed) continue;
    const std::string file = "deformed-" + name + ".stl";
    write_stl(ctx.output_dir / file, *deformed,
              fmt::format("fibermold {} deformed, target {} (mm)", d.design.name, name));
    const SurfaceCheck check = check_surface(*deformed);
    Json entry{{"target", name}, {"file", file}, {"volume_mL", check.volume / 1e-6}, {"checks_passed", check.ok()}};
    std::string pressures;
    const auto row = std::find(fibers.targets.begin(), fibers.targets.end(), name) - fibers.targets.begin();
    for (std::size_t f = 0; f < fibers.routing.routes.size() && row < std::ssize(fibers.targets); ++f)
      pressures += fmt::format("{}{} {:.0f} kPa", pressures.empty() ? "" : ", ", fibers.routing.routes[f].name,
                               fibers.routing.pressures(row, static_cast<Eigen::Index>(f)) / units::kPa);
    text += fmt::format("\nTarget \"{}\": drive the muscles at {} gauge (at most {:.0f} kPa, [muscle] max_pressure).\n"
                        "  {} is the body as simulated at these pressures, in the frame of the robot as\n"
                        "  mounted (its fixed faces where they are at rest). Print it, hold its fixed end against\n"
                        "  the robot's mount beside the pressurized robot, and compare:\n",
                        name, pressures.empty() ? "no pressure" : pressures, d.muscle.max_pressure / units::kPa, file);
    if (collide && (*collide)["targets"].contains(name))
      text += poses_to_compare((*collide)["targets"][name].value("poses", Json::array()));
    for (const SurfaceProblem& problem : check.problems) {
      text += fmt::format("  Note: the simulated body {} (e.g. at {}): the simulation has no self-contact; a slicer\n"
                          "  merges the overlap.\n",
                          problem.message, format_mm(problem.where));
      ctx.log.warn("{}: the simulated body {} (e.g. at {})", file, problem.message, format_mm(problem.where));
      entry["problems"].push_back(problem.message);
    }
    files.push_back(std::move(entry));
  }
  return text.empty() ? text : "\nChecking the cast robot against the simulation\n" + text;
}

/// README.txt's paragraph on the muscles' bends, from collide's report: the fibers as cast must not be
/// bent tighter than the muscle takes where they are laid into their grooves. Empty without it.
std::string muscle_bends_text(const StageContext& ctx)
{
  const auto report = json_if_any(ctx.upstream("collide", "report.json"));
  if (!report || !report->contains("bends") || !(*report)["min_bend_radius_mm"].is_number()) return {};
  std::string text = "\n";
  text += wrapped(fmt::format("The muscles take bends no tighter than {:.1f} mm in radius ([muscle] min_bend_radius); "
                              "the grooves follow the routes, so lay each muscle along its groove without kinking it. "
                              "Each route's tightest bend:",
                              (*report)["min_bend_radius_mm"].get<double>()),
                  "", "");
  for (const auto& [fiber, b] : (*report)["bends"].items())
    text += b.contains("min_bend_radius_mm")
                ? fmt::format("  {}: {:.1f} mm, {:.1f} mm along it\n", fiber, b["min_bend_radius_mm"].get<double>(),
                              b["along_mm"].get<double>())
                : fmt::format("  {}: straight\n", fiber);
  return text;
}

/// How well the robot does its job, from collide's report: each target's error before and after the
/// collisions were resolved, and what collide changed.
std::vector<ReportTable> behaviour_tables(const StageContext& ctx)
{
  std::vector<ReportTable> out;
  const auto report = json_if_any(ctx.upstream("collide", "report.json"));
  if (!report) return out;
  const auto mm = [](const Json& v) { return v.is_number() ? fixed(v.get<double>(), 3) : std::string("–"); };
  if ((*report)["targets"].is_object() && !(*report)["targets"].empty()) {
    ReportTable targets{"Targets: error over the tracking curves and the surface (mm)",
                        {"target", "RMSE before collide", "RMSE after", "change", "max before", "max after",
                         "surface RMSE after", "surface max after"},
                        {}};
    for (const auto& [name, t] : (*report)["targets"].items())
      targets.rows.push_back({name, mm(t["before"]["rmse_mm"]), mm(t["after"]["rmse_mm"]),
                              t["rmse_change_percent"].is_number()
                                  ? fmt::format("{:+.1f} %", t["rmse_change_percent"].get<double>())
                                  : "–",
                              mm(t["before"]["max_error_mm"]), mm(t["after"]["max_error_mm"]),
                              mm(t["after"]["surface_rmse_mm"]), mm(t["after"]["surface_max_error_mm"])});
    out.push_back(std::move(targets));
  }
  ReportTable collisions{"Collisions", {"between", "clearance before (mm)", "at (mm)"}, {}};
  for (const Json& c : (*report)["collisions"]) {
    std::string between;
    for (const Json& n : c["between"]) between += (between.empty() ? "" : " and ") + n.get<std::string>();
    std::string at;
    for (const Json& v : c["at_mm"])
      at += (at.empty() ? "" : ", ") + (v.is_number() ? fixed(v.get<double>(), 1) : std::string("–"));
    collisions.rows.push_back({between, mm(c["clearance_mm"]), "(" + at + ")"});
  }
  if (collisions.rows.empty()) collisions.rows.push_back({"none: every fiber was clear", "", ""});
  out.push_back(std::move(collisions));
  ReportTable moves{fmt::format("Collide: smallest clearance {} → {} mm (asked {} mm); {} round(s){}",
                                mm((*report)["smallest_clearance_mm"].value("before", Json())),
                                mm((*report)["smallest_clearance_mm"].value("after", Json())),
                                mm((*report)["clearance_mm"]), (*report)["rounds"].get<int>(),
                                (*report)["reoptimized"].get<bool>() ? ", optimized again" : ""),
                    {"fiber", "largest control point move (mm)", "largest tangent change (mm)"},
                    {}};
  for (const auto& [fiber, m] : (*report)["moves_mm"].items()) {
    double point = 0, tangent = 0;
    for (const Json& v : m["points"]) point = std::max(point, v.is_number() ? v.get<double>() : 0.0);
    for (const Json& v : m["tangents"]) tangent = std::max(tangent, v.is_number() ? v.get<double>() : 0.0);
    moves.rows.push_back({fiber, fixed(point, 3), fixed(tangent, 3)});
  }
  out.push_back(std::move(moves));
  // Each fiber's tightest bend as it will be cast, against the muscle's limit.
  ReportTable bends{fmt::format("Bend radius: each fiber's smallest, as built (the muscle takes {} mm)",
                                mm((*report)["min_bend_radius_mm"])),
                    {"fiber", "smallest bend radius (mm)", "at (mm)", "along the fiber (mm)"},
                    {}};
  for (const auto& [fiber, b] : (*report)["bends"].items()) {
    if (!b.contains("min_bend_radius_mm")) {
      bends.rows.push_back({fiber, "straight", "", ""});
      continue;
    }
    std::string at;
    for (const Json& v : b["at_mm"]) at += (at.empty() ? "" : ", ") + mm(v);
    bends.rows.push_back({fiber, mm(b["min_bend_radius_mm"]), "(" + at + ")", mm(b["along_mm"])});
  }
  if (!bends.rows.empty()) out.push_back(std::move(bends));
  return out;
}

/// How the optimization ended, from optimize/report.json: per target the error at the start and at
/// the end, how much of it was reached and each fiber's pressure; and its warnings, for the banner.
/// optimize/report.json where it optimized targets; none otherwise.
std::optional<Json> optimization_report(const StageContext& ctx)
{
  auto report = json_if_any(ctx.upstream("optimize", "report.json"));
  if (!report || !report->value("optimized", false) || !report->contains("targets") ||
      !(*report)["targets"].is_object() || (*report)["targets"].empty())
    return std::nullopt;
  return report;
}

/// The optimization's warnings (a target far from reached, a muscle at its limit, no convergence):
/// report.html's banner, and a paragraph of README.txt.
std::vector<std::string> optimization_warnings(const Json& report)
{
  std::vector<std::string> out;
  for (const Json& w : report.value("warnings", Json::array()))
    if (w.is_string()) out.push_back(w.get<std::string>());
  return out;
}

/// README.txt's paragraph with the optimization's warnings, before the robot is checked against the
/// simulation; empty without any.
std::string optimization_warnings_text(const StageContext& ctx)
{
  std::string text;
  if (const auto report = optimization_report(ctx))
    for (const std::string& w : optimization_warnings(*report)) text += wrapped(w, "  - ", "    ");
  return text.empty() ? text
                      : "\nThe optimization warned (report.html gives its figures); the cast robot will do what the\n"
                        "simulation does, not what was asked:\n" +
                            text;
}

std::optional<ReportTable> optimization_table(const StageContext& ctx, std::vector<std::string>& warnings)
{
  const auto report = optimization_report(ctx);
  if (!report) return std::nullopt;
  const std::vector<std::string> warned = optimization_warnings(*report);
  warnings.insert(warnings.end(), warned.begin(), warned.end());
  const auto number = [](const Json& j, const char* key, int digits, const std::string& unit = "") {
    return j.is_object() && j.contains(key) && j[key].is_number() ? fixed(j[key].get<double>(), digits) + unit
                                                                  : std::string("–");
  };
  ReportTable t{fmt::format("Optimization: {} after {} iterations ({})", report->value("termination", std::string("?")),
                            report->value("iterations", 0), report->value("message", std::string())),
                {"target", "RMSE at the start (mm)", "RMSE at the end (mm)", "reached: 1 − end / start RMSE"},
                {}};
  std::vector<std::string> fibers; // every target's report names every fiber's pressure
  const Json& first = (*report)["targets"].begin().value();
  if (first.contains("pressure_kPa") && first["pressure_kPa"].is_object())
    for (const auto& [fiber, p] : first["pressure_kPa"].items()) {
      fibers.push_back(fiber);
      t.header.push_back(fiber + " (kPa)");
    }
  // A pose target's turns: "54.1° of 60.0° (pose[1])".
  const auto turns = [](const Json& target) {
    std::string out;
    if (target.contains("poses") && target["poses"].is_array())
      for (const Json& p : target["poses"])
        if (p.is_object() && p.contains("asked_rotation_deg") && p["asked_rotation_deg"].is_number() &&
            p.contains("rotation_about_asked_axis_deg") && p["rotation_about_asked_axis_deg"].is_number())
          out += fmt::format("{}{:.1f}° of {:.1f}° ({})", out.empty() ? "" : "; ",
                             p["rotation_about_asked_axis_deg"].get<double>(), p["asked_rotation_deg"].get<double>(),
                             p.value("place", std::string("?")));
    return out;
  };
  bool any_turn = false;
  for (const auto& [name, target] : (*report)["targets"].items()) any_turn = any_turn || !turns(target).empty();
  if (any_turn) t.header.insert(t.header.begin() + 4, "turn reached");
  for (const auto& [name, target] : (*report)["targets"].items()) {
    std::vector<std::string> row{name, number(target.value("start", Json::object()), "rmse_mm", 3),
                                 number(target, "rmse_mm", 3), number(target, "reached_percent", 0, " %")};
    if (any_turn) row.push_back(turns(target).empty() ? "–" : turns(target));
    for (const std::string& f : fibers)
      row.push_back(number(target.value("pressure_kPa", Json::object()), f.c_str(), 1));
    t.rows.push_back(std::move(row));
  }
  return t;
}

/// The optimizer's objective and distance term per iteration, from optimize/history.csv.
std::optional<ReportPlot> optimization_history(const StageContext& ctx)
{
  std::error_code ec;
  const std::filesystem::path file = ctx.upstream("optimize", "history.csv");
  if (!std::filesystem::exists(file, ec)) return std::nullopt;
  std::istringstream lines(read_file(file));
  std::string header;
  std::getline(lines, header);
  std::vector<std::string> columns;
  std::istringstream names(header);
  for (std::string c; std::getline(names, c, ',');) columns.push_back(c);
  const auto column = [&](const std::string& name) {
    return std::find(columns.begin(), columns.end(), name) - columns.begin();
  };
  const auto iteration = column("iteration"), objective = column("objective"), distance = column("distance");
  if (std::max({iteration, objective, distance}) >= std::ssize(columns)) return std::nullopt;
  ReportPlot plot{"Optimization", "iteration", "objective", {{"objective", {}}, {"distance term", {}}}, true};
  for (std::string line; std::getline(lines, line);) {
    std::vector<double> v;
    std::istringstream cells(line);
    for (std::string cell; std::getline(cells, cell, ',');) v.push_back(std::strtod(cell.c_str(), nullptr));
    if (std::ssize(v) < std::ssize(columns)) continue;
    plot.series[0].second.emplace_back(v[iteration], v[objective]);
    plot.series[1].second.emplace_back(v[iteration], v[distance]);
  }
  if (plot.series[0].second.empty()) return std::nullopt;
  return plot;
}

/// Which hole is which: each sprue and vent of a shot drawn as a line through its half, from where it
/// meets the cavity out along the pull (a sprue from below: down through the lower half), named, the
/// sprue orange and the vents cyan; the parts of the shot sit at `offset`, its upper half 1.5 ×
/// `height` further along the pull (report()).
void add_ports(const Json& fill, const std::string& shot, const Eigen::Vector3d& pull, double height,
               const Eigen::Vector3d& offset, std::vector<ReportLine>& lines)
{
  const auto mouth = [](const Json& port) {
    const Json& p = port["mouth_mm"];
    const double x = p[0].get<double>(), y = p[1].get<double>(), z = p[2].get<double>();
    return Eigen::Vector3d(x * units::mm, y * units::mm, z * units::mm);
  };
  const bool shown = shot == "shot1";
  for (const Json& sprue : fill["sprues"]) {
    const bool below = sprue.value("from", std::string("below")) == "below";
    const Eigen::Vector3d at = mouth(sprue) + offset + (below ? 0.0 : 1.5 * height) * pull;
    lines.push_back({fmt::format("{} sprue, from {}", shot, below ? "below" : "above"),
                     {at, at + (below ? -height : height) * pull},
                     {1.0F, 0.55F, 0.0F},
                     shown});
  }
  int k = 0;
  for (const Json& vent : fill["vents"]) {
    const Eigen::Vector3d at = mouth(vent) + offset + 1.5 * height * pull;
    lines.push_back({fmt::format("{} vent {}", shot, ++k), {at, at + height * pull}, {0.0F, 0.7F, 0.8F}, shown});
  }
}

/// What a part carries engraved, for the parts table: "“WALKING-ROBOT S1 LOWER” (side, 8 mm) · “IN” (end,
/// 5 mm)", or "none".
std::string engraved_text(const Json& labels)
{
  std::vector<std::string> out;
  for (const Json& l : labels)
    out.push_back(fmt::format("“{}” ({}, {:g} mm)", l["text"].get<std::string>(), l["face"].get<std::string>(),
                              l["height_mm"].get<double>()));
  return out.empty() ? "none" : fmt::format("{}", fmt::join(out, " · "));
}

/// The page users open first: the groove body with its muscles in the shot 1 mold (upper half
/// lifted off along pull), the shot 2 mold beside it (hidden), the parts' checks and the silicone.
/// No timings (they are in make's output and the stage logs): the same design gives the same page.
std::string report(const StageContext& ctx, const TetMesh& body, const FibersFile& fibers, const Json& molds,
                   const Json& parts, const CastingSheet& sheet)
{
  const Design& d = ctx.design;
  const auto load = [&](const std::string& file) { return import_surface(ctx.upstream("molds", file), units::mm); };
  std::vector<ReportMesh> meshes;
  meshes.push_back(
      {"groove body (shot 1)", load("groove-body.stl"), {0.93F, 0.55F, 0.45F}, true, Eigen::Vector3d::Zero()});
  double width = 0, height = 0;
  for (const auto& [name, info] : molds["parts"].items()) {
    const Eigen::Vector3d size(info["size_mm"][0], info["size_mm"][1], info["size_mm"][2]);
    width = std::max(width, size.maxCoeff() * units::mm);
    height = std::max(height, size.minCoeff() * units::mm);
  }
  const Eigen::Vector3d pull = molds_pull(molds);
  const Eigen::Vector3d aside =
      (pull.cross(Eigen::Vector3d::UnitZ()).norm() > 0.5 ? pull.cross(Eigen::Vector3d::UnitZ())
                                                         : pull.cross(Eigen::Vector3d::UnitX()))
          .normalized();
  for (const auto& [name, info] : molds["parts"].items()) {
    const bool shot1 = info["shot"] == "shot1", upper = name.find("upper") != std::string::npos;
    const Eigen::Vector3d offset = (upper ? 1.5 * height : 0.0) * pull + (shot1 ? 0.0 : 1.3 * width) * aside;
    meshes.push_back({name, load(info["file"].get<std::string>()),
                      upper ? std::array{0.55F, 0.65F, 0.8F} : std::array{0.45F, 0.55F, 0.7F}, shot1, offset});
  }
  std::vector<ReportLine> lines = fiber_lines(fibers);
  for (const auto& [shot, info] : molds["shots"].items())
    add_ports(info["fill"], shot, pull, height, (shot == "shot1" ? 0.0 : 1.3 * width) * aside, lines);
  add_bodies(ctx, body, -1.3 * width * aside, -1.3 * width * aside, meshes, lines);

  ReportTable checks{
      "Mold parts",
      {"part", "files", "engraved", "triangles", "volume (mL)", "thinnest wall (mm)", "fits the printer", "checks"},
      {}};
  for (const Json& p : parts) {
    std::string files;
    for (const Json& f : p["files"]) files += (files.empty() ? "" : ", ") + f.get<std::string>();
    checks.rows.push_back({p["name"], files, engraved_text(p["labels"]), std::to_string(p["triangles"].get<long>()),
                           fixed(p["volume_mL"], 2), fixed(p["min_wall_mm"], 2),
                           p["fits_printer_as_placed"].get<bool>() ? "lying flat" : "turned",
                           p["checks_passed"].get<bool>() ? "passed" : "FAILED"});
  }
  std::vector<std::string> warnings;
  std::vector<ReportTable> tables;
  if (auto optimized = optimization_table(ctx, warnings)) tables.push_back(std::move(*optimized));
  for (ReportTable& t : behaviour_tables(ctx)) tables.push_back(std::move(t));
  tables.insert(tables.end(), {checks, silicone_table(sheet), muscles_table(sheet)});
  std::vector<ReportPlot> plots;
  if (auto history = optimization_history(ctx)) plots.push_back(std::move(*history));
  return report_html("fibermold: " + d.design.name, meshes, lines, tables, plots, warnings);
}

} // namespace

void ExportStage::run(StageContext& ctx) const
{
  const Design& d = ctx.design;
  const Json molds = Json::parse(read_file(ctx.upstream("molds", "report.json")));
  Json parts = Json::array();
  for (const auto& [name, info] : molds["parts"].items()) {
    ctx.progress.checkpoint(-1, "laying out " + name);
    const SurfaceMesh part = import_surface(ctx.upstream("molds", info["file"].get<std::string>()), units::mm);
    const Placement placed = lay_flat(part, d.export_.printer_volume);
    Json files = Json::array();
    for (const std::string& format : d.export_.formats) {
      const std::string file = name + "." + format;
      if (format == "3mf")
        write_3mf(ctx.output_dir / file, placed.part, name);
      else
        write_stl(ctx.output_dir / file, placed.part, fmt::format("fibermold {} {} (mm)", d.design.name, name));
      files.push_back(file);
    }
    parts.push_back(
        {{"name", name},
         {"shot", info["shot"]},
         {"file", files[0]},
         {"files", files},
         {"size_mm", {placed.size.x() / units::mm, placed.size.y() / units::mm, placed.size.z() / units::mm}},
         {"lies_on_mm2", placed.flat_area / 1e-6},
         {"fits_printer_as_placed", placed.fits},
         {"volume_mL", info["volume_mL"]},
         {"triangles", placed.part.num_faces()},
         {"min_wall_mm", info["min_wall_mm"]},
         {"checks_passed", info["checks_passed"]},
         {"labels", info.value("labels", Json::array())},
         {"from_body_frame", placement_json(placed)}});
    if (!placed.fits)
      ctx.log.warn("part {} does not fit the printer lying flat; its best fit turns it: axes {}", name,
                   info["print_axes"].dump());
  }
  Json shots = Json::object();
  for (const auto& [shot, info] : molds["shots"].items())
    shots[shot] = {{"silicone_volume_mL", info["silicone_volume_mL"]},
                   {"silicone_mass_g", info["silicone_mass_g"]},
                   {"fill", info["fill"]}};
  ctx.progress.checkpoint(-1, "writing the deformed bodies");
  Json deformed = Json::array();
  const TetMesh body = load_tet_mesh(ctx.upstream("mesh", "body.tetmesh"));
  const FibersFile fibers = read_fibers_json(ctx.upstream("collide", "fibers.json"));
  const std::string checking = overlay_shapes(ctx, body, fibers, deformed);
  const Json manifest{{"design", d.design.name}, {"units", "mm"},  {"voxel_mm", molds["voxel_mm"]},
                      {"parts", parts},          {"shots", shots}, {"deformed", deformed}};
  write_json_atomic(ctx.output_dir / "manifest.json", manifest);
  const CastingSheet sheet = casting_sheet(d, molds, muscle_cuts(ctx, body, fibers, molds));
  write_file_atomic(ctx.output_dir / "README.txt",
                    casting_guide(sheet) + muscle_bends_text(ctx) + optimization_warnings_text(ctx) + checking);
  ctx.progress.checkpoint(-1, "writing the report");
  write_file_atomic(ctx.output_dir / "report.html", report(ctx, body, fibers, molds, parts, sheet));
}

} // namespace fibermold
