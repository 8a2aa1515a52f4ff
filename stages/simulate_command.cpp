#include "stages/simulate_command.hpp"

#include "stages/design_mesh.hpp"
#include "stages/design_simulation.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>

#include <fmt/format.h>

#include "core/input_error.hpp"
#include "core/units.hpp"
#include "export/behaviour_summary.hpp"
#include "make/stamp.hpp"
#include "mesh/mesh_quality.hpp"
#include "mesh/tet_mesh.hpp"
#include "optimize/tracking_curve.hpp"
#include "sim/external_forces.hpp"
#include "sim/mls_basis.hpp"
#include "sim/muscle_energy.hpp"
#include "sim/neo_hookean.hpp"
#include "sim/simulation.hpp"
#include "stages/fibers_file.hpp"
#include "stages/target_poses.hpp"

namespace fibermold {

namespace fs = std::filesystem;

namespace {

[[noreturn]] void bad(const Design& d, const std::string& key, const std::string& message)
{
  throw InputError(design_problem(d, key, message));
}

/// "flexor 300 kPa, extensor 0 kPa": the muscles' pressures as the run's lines give them.
std::string pressure_list(const std::vector<Actuation>& actuations)
{
  std::string out;
  for (const Actuation& a : actuations)
    out += fmt::format("{}{} {:.0f} kPa", out.empty() ? "" : ", ", a.fiber, a.pressure / units::kPa);
  return out;
}

/// Every [[fiber]] in the design's order, at its --pressure or, not given one, at 0 kPa: the cast
/// robot holds every muscle, and one at rest stiffens the body all the same (a new user's 90 mm finger
/// sagged 66.9 mm with its one muscle left out, 57.7 mm with it at 0 kPa; session 39).
std::vector<Actuation> requested_actuations(const Design& d, const SimulateRequest& request)
{
  std::vector<Actuation> out;
  const auto fiber = [&](const std::string& name) -> const Fiber* {
    for (const Fiber& f : d.fibers)
      if (f.name == name) return &f;
    return nullptr;
  };
  for (const std::string& item : request.pressures) {
    const auto eq = item.find('=');
    const std::string name = item.substr(0, eq);
    double kpa = NAN;
    const std::string value = eq == std::string::npos ? std::string() : item.substr(eq + 1);
    // The whole value a decimal number: "300Pa", "0.3MPa" or "2bar" would otherwise read as 300, 0.3
    // or 2 kPa; from_chars takes no hexadecimal ("0x12c"), leading space or sign.
    const auto [end, error] = std::from_chars(value.data(), value.data() + value.size(), kpa);
    if (eq == std::string::npos || error != std::errc() || end != value.data() + value.size() || !std::isfinite(kpa))
      bad(d, "--pressure", fmt::format("'{}': expected FIBER=kPa, the pressure a number in kPa without a unit", item));
    const Fiber* f = fiber(name);
    if (!f) {
      std::vector<std::string> names;
      for (const Fiber& each : d.fibers) names.push_back(each.name);
      bad(d, "--pressure",
          fmt::format("no [[fiber]] named \"{}\" (the design has {})", name,
                      names.empty() ? std::string("none") : fmt::format("{}", fmt::join(names, ", "))));
    }
    if (kpa < 0 || kpa * units::kPa > d.muscle.max_pressure)
      bad(d, "--pressure",
          fmt::format("{} kPa for {} is outside [0, {}] kPa ([muscle].max_pressure)", kpa, name,
                      d.muscle.max_pressure / units::kPa));
    if (std::any_of(out.begin(), out.end(), [&](const Actuation& a) { return a.fiber == name; }))
      bad(d, "--pressure", fmt::format("{} is given twice", name));
    out.push_back({name, f->points, f->tangents, kpa * units::kPa, true});
  }
  std::vector<Actuation> all;
  for (const Fiber& f : d.fibers) {
    const auto given = std::find_if(out.begin(), out.end(), [&](const Actuation& a) { return a.fiber == f.name; });
    all.push_back(given != out.end() ? *given : Actuation{f.name, f.points, f.tangents, 0.0, true});
  }
  return all;
}

/// "-flexor-300kPa": the pressures given on the command line, in their order, so that runs at other
/// pressures write files of their own ("pressures-flexor-300kPa", "curl-flexor-300kPa-as-built"; until
/// session 42 each overwrote deformed-pressures.vtu).
std::string pressures_name(const std::vector<std::string>& given, const std::vector<Actuation>& actuations)
{
  std::string name;
  for (const std::string& item : given) {
    const std::string fiber = item.substr(0, item.find('='));
    for (const Actuation& a : actuations)
      if (a.fiber == fiber) name += fmt::format("-{}-{:g}kPa", fiber, a.pressure / units::kPa);
  }
  return name;
}

/// The fibers given a --pressure, in their order (requested_actuations has checked each "FIBER=kPa").
std::vector<std::string> given_fibers(const SimulateRequest& request)
{
  std::vector<std::string> out;
  for (const std::string& item : request.pressures) out.push_back(item.substr(0, item.find('=')));
  return out;
}

/// --as-built: the routes of collide/fibers.json in place of the design's, and with a target its
/// pressures there, each fiber of `given` (its --pressure) at its own. InputError when the build folder
/// was made from another body, when the file is missing or unreadable, or does not hold a fiber or the
/// target the request names.
std::vector<Actuation> as_built(const Design& d, const fs::path& build_dir, const Target* target,
                                std::vector<Actuation> requested, const std::vector<std::string>& given,
                                std::string& said)
{
  const fs::path path = build_dir / "collide" / "fibers.json";
  const auto refuse = [&](const std::string& message) {
    throw InputError(Diagnostic{path, 0, 0, "--as-built", message});
  };
  const std::string elsewhere = fmt::format("give --build-dir the folder {}'s molds were made in", d.design.name);
  // Before anything is meshed there: a folder of another body's molds is not this robot's.
  if (const auto mesh = Stamp::load(Runner::stamp_path(build_dir, "mesh"));
      mesh && !mesh->files.empty() && !mesh->files.count(d.design.surface.string()))
    refuse(fmt::format("this build folder was made from {}, not from {}'s surface {}: {}", mesh->files.begin()->first,
                       d.design.name, d.design.surface.string(), elsewhere));
  if (!fs::exists(path))
    refuse(fmt::format("does not exist. --as-built reads the routes the molds were made for from the build folder "
                       "they were made in: {} (by default out/{} under the folder you run in). If no molds were "
                       "made yet, `fibermold make {} collide` routes the muscles first",
                       elsewhere, d.design.name, d.file.string()));
  FibersFile file;
  try {
    file = read_fibers_json(path);
  } catch (const std::runtime_error& e) { // "<path>: not a fibers file: …", the path given once
    const std::string what = e.what(), prefix = path.string() + ": ";
    refuse(what.rfind(prefix, 0) == 0 ? what.substr(prefix.size()) : what);
  }
  for (const Route& r : file.routing.routes)
    if (std::none_of(d.fibers.begin(), d.fibers.end(), [&](const Fiber& f) { return f.name == r.name; }))
      refuse(fmt::format("holds fiber \"{}\", which the design has not: its molds were made for another design, or "
                         "before the fiber was named so; {}",
                         r.name, elsewhere));
  const auto route = [&](const std::string& name) {
    const auto r = std::find_if(file.routing.routes.begin(), file.routing.routes.end(),
                                [&](const Route& each) { return each.name == name; });
    if (r == file.routing.routes.end())
      refuse(fmt::format("holds no fiber \"{}\": its molds were made for another design, or before the fiber was "
                         "named so; {}",
                         name, elsewhere));
    return r;
  };
  said = fmt::format("as built: the routes of {}", path.string());
  if (!target) { // the file's muscles, each at its --pressure or at rest; a fiber named must be among them
    const auto given = [&](const std::string& name) {
      return std::find_if(requested.begin(), requested.end(), [&](const Actuation& a) { return a.fiber == name; });
    };
    for (const Actuation& a : requested)
      if (a.pressure > 0) route(a.fiber);
    std::vector<Actuation> out;
    for (const Route& r : file.routing.routes) {
      const auto a = given(r.name);
      out.push_back({r.name, r.points, r.tangents, a != requested.end() ? a->pressure : 0.0});
    }
    return out;
  }
  const auto row = std::find(file.targets.begin(), file.targets.end(), target->name);
  if (row == file.targets.end())
    refuse(fmt::format("holds no pressures for target \"{}\" (it has {}): its molds were made for another design, "
                       "or before the target was named so; {}",
                       target->name,
                       file.targets.empty() ? std::string("none") : fmt::format("{}", fmt::join(file.targets, ", ")),
                       elsewhere));
  for (const std::string& name : given) route(name);
  std::vector<Actuation> out, changed, kept;
  for (std::size_t k = 0; k < file.routing.routes.size(); ++k) {
    const Route& r = file.routing.routes[k];
    double p = file.routing.pressures(row - file.targets.begin(), static_cast<Eigen::Index>(k));
    const bool was_given = std::find(given.begin(), given.end(), r.name) != given.end();
    if (was_given)
      p = std::find_if(requested.begin(), requested.end(), [&](const Actuation& a) {
            return a.fiber == r.name;
          })->pressure;
    else if (!(p >= 0 && p <= d.muscle.max_pressure))
      refuse(fmt::format("fiber {}: target {}'s pressure {:.0f} kPa is outside [0, {:.0f}] kPa ([muscle].max_pressure)",
                         r.name, target->name, p / units::kPa, d.muscle.max_pressure / units::kPa));
    out.push_back({r.name, r.points, r.tangents, p});
    (was_given ? changed : kept).push_back(out.back());
  }
  if (changed.empty())
    said += fmt::format(", at target {}'s pressures there ({})", target->name, pressure_list(out));
  else
    said += fmt::format(", target {}'s regions at the pressures given ({}{})", target->name, pressure_list(changed),
                        kept.empty() ? "" : "; the others at the target's there: " + pressure_list(kept));
  return out;
}

/// The design's body on `mesh` under the request's load, at equilibrium.
struct Solved {
  std::unique_ptr<MuscleModel> model; ///< before sim: its muscles hold a reference to it
  std::unique_ptr<Simulation> sim;
  std::vector<const MuscleEnergy*> muscles;
  Eigen::VectorXd x;
  NewtonSummary summary;
};

Solved solve(const Design& d, const TetMesh& mesh, const Target* target, const std::vector<Actuation>& actuations,
             Progress& progress)
{
  Solved out;
  out.sim = std::make_unique<Simulation>(mesh, simulation_options(d, mesh));
  if (target && target->kind == TargetKind::forces)
    out.sim->add_energy(std::make_unique<ExternalForces>(target_forces(d, *target, *out.sim)));
  out.model = std::make_unique<MuscleModel>(d.muscle.model);
  out.muscles = add_muscles(*out.sim, d, *out.model, actuations);
  out.x = out.sim->rest();
  out.summary = out.sim->solve(out.x, progress);
  if (!out.summary.converged)
    throw std::runtime_error(fmt::format("the simulation did not reach equilibrium on {} tets: {} ({})",
                                         mesh.num_tets(), out.summary.brief(), out.summary.message));
  return out;
}

/// Where the target's regions (its loads' or poses') and the tracking curves' ends went, as README.txt
/// gives them to compare with the cast robot; without a target (--pressure, or none), the curves' ends.
std::string compared_poses(const Design& d, const Target* target, const TetMesh& mesh, const Simulation& sim,
                           const Eigen::VectorXd& x)
{
  const Target none; // no region of its own
  const Target& t = target ? *target : none;
  const std::vector<PosedRegion> asked =
      t.kind == TargetKind::pose ? target_poses(d, t, mesh) : std::vector<PosedRegion>{};
  nlohmann::ordered_json poses = nlohmann::ordered_json::array();
  for (const ReachedPose& r : reached_poses(d, t, sim, x, asked)) poses.push_back(pose_report(r));
  return poses.empty() ? std::string() : poses_to_compare(poses);
}

} // namespace

SimulateResult simulate(const Design& d, const Runner& runner, const fs::path& build_dir,
                        const SimulateRequest& request, const ProgressFactory& progress)
{
  if (!request.target.empty() && !request.pressures.empty() && !request.as_built)
    bad(d, "--target",
        "give either --target or --pressure, not both (with --as-built, both: the target's regions with its "
        "pressures there, those given at theirs)");
  const Target* target = nullptr;
  for (const Target& t : d.targets)
    if (t.name == request.target) target = &t;
  if (!request.target.empty() && !target) {
    std::vector<std::string> names;
    for (const Target& t : d.targets) names.push_back(t.name);
    bad(d, "--target",
        fmt::format("no [[target]] named \"{}\" (the design has {})", request.target,
                    names.empty() ? std::string("none") : fmt::format("{}", fmt::join(names, ", "))));
  }
  if (request.as_built && !target && request.pressures.empty())
    bad(d, "--as-built", "give --target NAME (the pressures the molds' routing has for it) or --pressure FIBER=kPa");
  if (target && target->kind == TargetKind::surface && !request.as_built)
    bad(d, "--target",
        fmt::format("target \"{}\" is a deformed surface, not a load: nothing to simulate (--as-built simulates "
                    "the pressures found for it)",
                    target->name));
  if (target && target->kind == TargetKind::pose && !request.as_built)
    bad(d, "--target",
        fmt::format("target \"{}\" is a pose, not a load: `fibermold make DESIGN targets` fills it in "
                    "(targets/{}.vtu); --as-built simulates the pressures found for it",
                    target->name, target->name));
  // A target's loads act on the body alone (as the targets stage makes its shape); pressures on the robot.
  std::vector<Actuation> actuations =
      target && request.pressures.empty() ? std::vector<Actuation>{} : requested_actuations(d, request);
  if (target && target->kind == TargetKind::fibers && !request.as_built) actuations = target_actuations(d, *target);
  std::string as_built_said;
  if (request.as_built)
    actuations = as_built(d, build_dir, target, std::move(actuations), given_fibers(request), as_built_said);
  // As built, a target is reached by the muscles alone: its forces or known fibers made its shape.
  const Target* load = request.as_built ? nullptr : target;

  runner.make(d, {build_dir, {"mesh"}, false}, progress);
  const TetMesh mesh = load_tet_mesh(build_dir / "mesh" / "body.tetmesh");
  std::unique_ptr<Progress> reporter = progress ? progress("simulate") : nullptr;
  NullProgress silent;
  Progress& p = reporter ? *reporter : silent;
  const Solved coarse = [&] {
    try {
      return solve(d, mesh, load, actuations, p);
    } catch (const InputError& e) { // a route of collide/fibers.json that today's body does not hold
      if (!request.as_built) throw;
      std::vector<Diagnostic> said = e.diagnostics();
      for (Diagnostic& each : said)
        each.message += fmt::format(" (the route as built, {}: the body or its mesh changed since)",
                                    (build_dir / "collide" / "fibers.json").string());
      throw InputError(said);
    }
  }();

  SimulateResult result;
  result.name = fmt::format("{}{}{}",
                            target                      ? target->name
                            : request.pressures.empty() ? std::string("unactuated")
                                                        : "pressures",
                            pressures_name(request.pressures, actuations), request.as_built ? "-as-built" : "");
  result.muscles = actuations.empty() ? std::string("no muscle: the body under ") +
                                            (load ? "the target's loads, its weight and its held regions"
                                                  : "its weight and its held regions")
                                      : "muscles: ";
  result.muscles += pressure_list(actuations);
  if (request.as_built)
    result.as_built =
        fmt::format("{}; [material] youngs_modulus {:.0f} Pa, poisson_ratio {:g}, density {:g} kg/m³", as_built_said,
                    d.material.youngs_modulus, d.material.poisson_ratio, d.material.density);
  result.poses = compared_poses(d, target, mesh, *coarse.sim, coarse.x);
  result.summary = coarse.summary;
  result.max_displacement = (coarse.sim->deformed_nodes(coarse.x) - mesh.nodes).rowwise().norm().maxCoeff();
  if (const auto* mls = dynamic_cast<const MlsBasis*>(&coarse.sim->basis()); mls && mls->conditioning().widened > 0) {
    const MlsConditioning c = mls->conditioning();
    result.conditioning = fmt::format("MLS radius widened at {} points (too few or co-planar nodes), e.g. at {}, up to "
                                      "{:.3g} mm; consider a finer mesh there or a larger [sim] mls_radius",
                                      c.widened, format_mm(c.example), c.largest_radius / units::mm);
  }
  result.vtu = build_dir / "simulate" / fmt::format("deformed-{}.vtu", result.name);
  write_deformed(result.vtu, *coarse.sim, coarse.x, coarse.muscles,
                 LameParameters::from_young_poisson(d.material.youngs_modulus, d.material.poisson_ratio));
  if (request.refine) {
    p.checkpoint(-1, "meshing at half the edge length");
    const TetMesh fine_mesh = refined_design_mesh(d, p);
    const Solved fine = solve(d, fine_mesh, load, actuations, p);
    result.refinement = compare_refined(d, *coarse.sim, coarse.x, *fine.sim, fine.x);
    write_deformed(build_dir / "simulate" / fmt::format("deformed-{}-refined.vtu", result.name), *fine.sim, fine.x,
                   fine.muscles,
                   LameParameters::from_young_poisson(d.material.youngs_modulus, d.material.poisson_ratio));
  }
  return result;
}

} // namespace fibermold
