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
#include "core/shell_words.hpp"
#include "core/units.hpp"
#include "core/wrapped_text.hpp"
#include "export/behaviour_summary.hpp"
#include "export/casting_sheet.hpp"
#include "export/deformed_body.hpp"
#include "export/lay_flat.hpp"
#include "export/mold_parts_summary.hpp"
#include "export/muscle_cut.hpp"
#include "export/optimization_summary.hpp"
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
#include "stages/target_poses.hpp"

namespace fibermold {

namespace {

using Json = nlohmann::ordered_json;
namespace fs = std::filesystem;

std::vector<ReportLine> fiber_lines(const FibersFile& fibers);

/// The pull the molds were made for (molds/report.json): [mold] pull, or its reverse where that left
/// a half of shot 1 a plate.
Eigen::Vector3d molds_pull(const Json& molds)
{
  return molds.contains("pull") ? Eigen::Vector3d(molds["pull"][0], molds["pull"][1], molds["pull"][2])
                                : Eigen::Vector3d::UnitZ();
}

/// Each [[fixed]] region's nodes.
std::vector<std::vector<int>> held_nodes(const Design& d, const TetMesh& body)
{
  std::vector<std::vector<int>> out;
  for (std::size_t i = 0; i < d.fixed.size(); ++i)
    out.push_back(region_nodes(d.fixed[i].region, body, d, fmt::format("fixed[{}]", i + 1)));
  return out;
}

/// Each fiber's cut: along its centre line as collide left it (10 points per mm), against the body's skin;
/// an end leaves the body within the groove's radius of the skin (molds/report.json), and the supply end
/// is the one nearest the [[fixed]] regions' centroid (`regions`: held_nodes).
std::vector<MuscleCut> muscle_cuts(const TetMesh& body, const std::vector<std::vector<int>>& regions,
                                   const FibersFile& fibers, const Json& molds)
{
  const SurfaceDistance skin(body.nodes, body.boundary_faces);
  std::optional<Eigen::Vector3d> mount;
  std::vector<int> held;
  for (const std::vector<int>& nodes : regions) held.insert(held.end(), nodes.begin(), nodes.end());
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
  for (const Json& rib : shot.value("thin_ribs", Json::array())) {
    HalfRibs& r = rib["half"].get<std::string>() == "upper" ? c.upper_ribs : c.lower_ribs;
    const double thickness = rib["thickness_mm"].get<double>() * units::mm,
                 depth = rib["depth_mm"].get<double>() * units::mm;
    r.thinnest = r.count == 0 ? thickness : std::min(r.thinnest, thickness);
    r.deepest = std::max(r.deepest, depth);
    ++r.count;
  }
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
  sheet.paper_material = m.preset.empty() && m.youngs_modulus == MaterialOptions{}.youngs_modulus &&
                         m.poisson_ratio == MaterialOptions{}.poisson_ratio && m.density == MaterialOptions{}.density;
  sheet.muscle_diameter = d.muscle.model.diameter;
  sheet.end_channel_diameter = d.mold.end_channel_diameter;
  sheet.end_channel_length = d.mold.end_channel_length;
  sheet.screw_diameter = d.mold.block.screw_diameter;
  sheet.draft = d.mold.draft_deg > 0;
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

/// What the export shows of the simulation, read once: collide's report, optimize's where it optimized
/// targets, and per [[target]] the body as collide left it (collide/deformed-<target>.json).
struct Simulated {
  std::optional<Json> collide, optimized;
  std::vector<std::optional<Json>> states;
};

Simulated read_simulated(const StageContext& ctx)
{
  Simulated s{read_json_if_any<Json>(ctx.upstream("collide", "report.json")),
              read_json_if_any<Json>(ctx.upstream("optimize", "report.json")),
              {}};
  if (s.optimized && !optimized_targets(*s.optimized)) s.optimized.reset();
  for (const Target& t : ctx.design.targets)
    s.states.push_back(read_json_if_any<Json>(ctx.upstream("collide", "deformed-" + t.name + ".json")));
  return s;
}

/// The body at rest and, per target, deformed under the final routing (collide/deformed-*.json),
/// with its fibers, at `offset`, and the target's own deformation (targets/<name>.json) beside it,
/// `beside` further; the first target's shown, the rest switched off; the tracking curves at rest.
void add_bodies(const StageContext& ctx, const TetMesh& body, const Simulated& simulated, const Eigen::Vector3d& offset,
                const Eigen::Vector3d& beside, std::vector<ReportMesh>& meshes, std::vector<ReportLine>& lines)
{
  bool first = true;
  for (std::size_t t = 0; t < ctx.design.targets.size(); ++t) {
    const Target& target = ctx.design.targets[t];
    const std::optional<Json>& state = simulated.states[t];
    std::optional<SurfaceMesh> deformed = deformed_body(body, state);
    if (!deformed) continue;
    meshes.push_back({"body, " + target.name, std::move(*deformed), {0.5F, 0.78F, 0.5F}, first, offset});
    if (std::optional<SurfaceMesh> asked =
            deformed_body(body, read_json_if_any<Json>(ctx.upstream("targets", target.name + ".json"))))
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

/// The command that simulates the cast robot again (`fibermold simulate --as-built`), run from the
/// design's folder: the build folder relative to it where it lies inside, else absolute.
std::string as_built_command(const Design& d, const fs::path& build_dir, const std::string& target)
{
  const fs::path build = fs::weakly_canonical(build_dir), folder = fs::weakly_canonical(d.folder);
  const fs::path relative = build.lexically_relative(folder);
  const bool inside = !relative.empty() && *relative.begin() != "..";
  return fmt::format("fibermold simulate {} --as-built --target {} --build-dir {}",
                     shell_word(d.file.filename().string()), shell_word(target),
                     shell_word((inside ? relative : build).string()));
}

/// Where the design holds the body, for whoever mounts the cast robot: each [[fixed]] region by its
/// name, its held nodes' centre and extent ("centre: 25 nodes around (0.0, 0.0, 0.4) mm, from
/// (-8.0, -8.0, 0.0) to (8.0, 8.0, 2.0) mm"). A body with no end (a starfish held at its
/// underside's centre) left "its fixed end" to a guess. `held`: held_nodes.
std::string held_regions(const Design& d, const TetMesh& body, const std::vector<std::vector<int>>& held)
{
  std::string out;
  for (std::size_t i = 0; i < held.size(); ++i) {
    const std::vector<int>& nodes = held[i];
    if (nodes.empty()) continue;
    Eigen::Vector3d lo = body.nodes.row(nodes.front()).transpose(), hi = lo, centre = Eigen::Vector3d::Zero();
    for (int n : nodes) {
      const Eigen::Vector3d p = body.nodes.row(n).transpose();
      lo = lo.cwiseMin(p), hi = hi.cwiseMax(p), centre += p / static_cast<double>(nodes.size());
    }
    out += fmt::format("{}{}: {} nodes around {}, from {} to {}", out.empty() ? "" : "; ", d.fixed[i].name,
                       nodes.size(), format_mm(centre), format_mm(lo), format_mm(hi));
  }
  return out.empty() ? "its [[fixed]] regions" : out;
}

/// Per target, the body as simulated under the final routing (collide/deformed-<target>.json), as a
/// printable STL in the body's frame, which is the frame of the robot as mounted (its [[fixed]]
/// regions stay where they are at rest); README.txt's section on checking the cast robot with it,
/// and the files for the manifest. `held`: held_regions, where the robot is mounted.
std::string overlay_shapes(const StageContext& ctx, const TetMesh& body, const std::string& held,
                           const FibersFile& fibers, const Simulated& simulated, Json& files)
{
  const Design& d = ctx.design;
  const std::optional<Json>& collide = simulated.collide;
  std::string text;
  for (std::size_t t = 0; t < d.targets.size(); ++t) {
    const std::string& name = d.targets[t].name;
    std::optional<SurfaceMesh> deformed = deformed_body(body, simulated.states[t]);
    if (!deformed) continue;
    const std::string file = "deformed-" + name + ".stl";
    write_stl(ctx.output_dir / file, *deformed,
              fmt::format("fibermold {} deformed, target {} (mm)", d.design.name, name));
    const SurfaceCheck check = check_surface(*deformed);
    Json entry{
        {"target", name}, {"file", file}, {"volume_mL", check.volume / units::mL}, {"checks_passed", check.ok()}};
    std::string pressures;
    bool beyond = false; // the higher pressure of collide's sensitivity above max_pressure for a muscle
    const auto row = std::find(fibers.targets.begin(), fibers.targets.end(), name) - fibers.targets.begin();
    for (std::size_t f = 0; f < fibers.routing.routes.size() && row < std::ssize(fibers.targets); ++f) {
      const double p = fibers.routing.pressures(row, static_cast<Eigen::Index>(f));
      pressures +=
          fmt::format("{}{} {:.0f} kPa", pressures.empty() ? "" : ", ", fibers.routing.routes[f].name, p / units::kPa);
      beyond = beyond || (1 + kSensitivityChange) * p > d.muscle.max_pressure;
    }
    text += '\n'; // (not "\n" + wrapped(…): GCC 12 warns a false -Wrestrict on it)
    text +=
        wrapped(fmt::format("Target \"{}\": drive the muscles at {} gauge (at most {:.0f} kPa, [muscle] "
                            "max_pressure).",
                            name, pressures.empty() ? "no pressure" : pressures, d.muscle.max_pressure / units::kPa),
                "", "  ");
    text += wrapped(fmt::format("{} is the body as simulated at these pressures, in the frame of the robot as mounted "
                                "(its fixed faces where they are at rest). Print it, hold it where the design holds "
                                "the robot ({}) against the robot's mount beside the pressurized robot, and compare:",
                                file, held),
                    "  ", "  ");
    if (collide && (*collide)["targets"].contains(name))
      text += poses_to_compare((*collide)["targets"][name].value("poses", Json::array())) +
              what_to_measure((*collide)["targets"][name].value("poses", Json::array()), d.material.youngs_modulus,
                              beyond, as_built_command(d, ctx.build_dir, name));
    for (const SurfaceProblem& problem : check.problems) {
      text += fmt::format("  Note: the simulated body {} (e.g. at {}): the simulation has no self-contact; a slicer\n"
                          "  merges the overlap.\n",
                          problem.message, format_mm(problem.where));
      ctx.log.warn("{}: the simulated body {} (e.g. at {})", file, problem.message, format_mm(problem.where));
      entry["problems"].push_back(problem.message);
    }
    files.push_back(std::move(entry));
  }
  if (text.empty()) return text;
  // How the robot hangs decides where its weight bends it: as simulated, or the figures do not hold.
  const Eigen::Vector3d g = d.material.gravity;
  const std::string hang =
      g.norm() > 0 ? fmt::format("Mount the robot as it was simulated: held at its fixed faces, with the design's "
                                 "direction ({:.2f}, {:.2f}, {:.2f}) pointing down ([material] gravity).",
                                 g.x() / g.norm() + 0.0, g.y() / g.norm() + 0.0, g.z() / g.norm() + 0.0)
                   : "The simulation leaves out the robot's weight ([material] gravity = [0, 0, 0]): support it so "
                     "that its weight does not bend it.";
  return "\nChecking the cast robot against the simulation\n" + wrapped(hang, "", "") + text;
}

/// The page users open first: the groove body with its muscles in the shot 1 mold (upper half
/// lifted off along pull), the shot 2 mold beside it (hidden), the parts' checks and the silicone.
/// No timings (they are in make's output and the stage logs): the same design gives the same page.
std::string report(const StageContext& ctx, const TetMesh& body, const FibersFile& fibers, const Simulated& simulated,
                   const Json& molds, const Json& parts, const CastingSheet& sheet)
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
    for (ReportLine& l : port_lines(info["fill"], shot, pull, height, (shot == "shot1" ? 0.0 : 1.3 * width) * aside))
      lines.push_back(std::move(l));
  add_bodies(ctx, body, simulated, -1.3 * width * aside, -1.3 * width * aside, meshes, lines);

  std::vector<std::string> warnings;
  std::vector<ReportTable> tables;
  if (simulated.optimized) {
    warnings = optimization_warnings(*simulated.optimized);
    tables.push_back(optimization_table(*simulated.optimized));
  }
  if (simulated.collide)
    for (ReportTable& t : behaviour_tables(*simulated.collide)) tables.push_back(std::move(t));
  tables.insert(tables.end(), {parts_table(parts), silicone_table(sheet), muscles_table(sheet)});
  std::vector<ReportPlot> plots;
  std::error_code ec;
  if (const auto history = ctx.upstream("optimize", "history.csv"); std::filesystem::exists(history, ec))
    if (auto plot = optimization_history(read_file(history))) plots.push_back(std::move(*plot));
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
         {"lies_on_mm2", placed.flat_area / units::mm2},
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
  const Simulated simulated = read_simulated(ctx);
  const std::vector<std::vector<int>> held = held_nodes(d, body);
  const std::string checking = overlay_shapes(ctx, body, held_regions(d, body, held), fibers, simulated, deformed);
  const Json manifest{{"design", d.design.name}, {"units", "mm"},  {"voxel_mm", molds["voxel_mm"]},
                      {"parts", parts},          {"shots", shots}, {"deformed", deformed}};
  write_json_atomic(ctx.output_dir / "manifest.json", manifest);
  const CastingSheet sheet = casting_sheet(d, molds, muscle_cuts(body, held, fibers, molds));
  write_file_atomic(ctx.output_dir / "README.txt",
                    casting_guide(sheet) + (simulated.collide ? muscle_bends_text(*simulated.collide) : std::string()) +
                        (simulated.optimized ? optimization_warnings_text(*simulated.optimized) : "") + checking);
  ctx.progress.checkpoint(-1, "writing the report");
  write_file_atomic(ctx.output_dir / "report.html", report(ctx, body, fibers, simulated, molds, parts, sheet));
}

} // namespace fibermold
