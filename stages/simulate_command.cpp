#include "stages/simulate_command.hpp"

#include "stages/design_mesh.hpp"
#include "stages/design_simulation.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/input_error.hpp"
#include "core/units.hpp"
#include "mesh/mesh_quality.hpp"
#include "mesh/tet_mesh.hpp"
#include "optimize/tracking_curve.hpp"
#include "sim/external_forces.hpp"
#include "sim/mls_basis.hpp"
#include "sim/muscle_energy.hpp"
#include "sim/neo_hookean.hpp"
#include "sim/simulation.hpp"

namespace fibermold {

namespace fs = std::filesystem;

namespace {

[[noreturn]] void bad(const Design& d, const std::string& key, const std::string& message)
{
  throw InputError(design_problem(d, key, message));
}

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
    try {
      if (eq != std::string::npos) kpa = std::stod(item.substr(eq + 1));
    } catch (const std::exception&) {
    }
    if (eq == std::string::npos || !std::isfinite(kpa))
      bad(d, "--pressure", fmt::format("'{}': expected FIBER=kPa", item));
    const Fiber* f = fiber(name);
    if (!f) bad(d, "--pressure", fmt::format("no [[fiber]] named \"{}\"", name));
    if (kpa < 0 || kpa * units::kPa > d.muscle.max_pressure)
      bad(d, "--pressure",
          fmt::format("{} kPa for {} is outside [0, {}] kPa ([muscle].max_pressure)", kpa, name,
                      d.muscle.max_pressure / units::kPa));
    if (std::any_of(out.begin(), out.end(), [&](const Actuation& a) { return a.fiber == name; }))
      bad(d, "--pressure", fmt::format("{} is given twice", name));
    out.push_back({name, f->points, f->tangents, kpa * units::kPa});
  }
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

} // namespace

SimulateResult simulate(const Design& d, const Runner& runner, const fs::path& build_dir,
                        const SimulateRequest& request, const ProgressFactory& progress)
{
  if (!request.target.empty() && !request.pressures.empty())
    bad(d, "--target", "give either --target or --pressure, not both");
  const Target* target = nullptr;
  for (const Target& t : d.targets)
    if (t.name == request.target) target = &t;
  if (!request.target.empty() && !target) bad(d, "--target", fmt::format("no [[target]] named \"{}\"", request.target));
  if (target && target->kind == TargetKind::surface)
    bad(d, "--target",
        fmt::format("target \"{}\" is a deformed surface, not a load: nothing to simulate", target->name));
  if (target && target->kind == TargetKind::pose)
    bad(d, "--target",
        fmt::format("target \"{}\" is a pose, not a load: `fibermold make DESIGN targets` fills it in "
                    "(targets/{}.vtu)",
                    target->name, target->name));
  std::vector<Actuation> actuations = requested_actuations(d, request);
  if (target && target->kind == TargetKind::fibers) actuations = target_actuations(d, *target);

  runner.make(d, {build_dir, {"mesh"}, false}, progress);
  const TetMesh mesh = load_tet_mesh(build_dir / "mesh" / "body.tetmesh");
  std::unique_ptr<Progress> reporter = progress ? progress("simulate") : nullptr;
  NullProgress silent;
  Progress& p = reporter ? *reporter : silent;
  const Solved coarse = solve(d, mesh, target, actuations, p);

  SimulateResult result;
  result.name = target ? target->name : "pressures";
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
    const Solved fine = solve(d, fine_mesh, target, actuations, p);
    result.refinement = compare_refined(d, *coarse.sim, coarse.x, *fine.sim, fine.x);
    write_deformed(build_dir / "simulate" / fmt::format("deformed-{}-refined.vtu", result.name), *fine.sim, fine.x,
                   fine.muscles,
                   LameParameters::from_young_poisson(d.material.youngs_modulus, d.material.poisson_ratio));
  }
  return result;
}

} // namespace fibermold
