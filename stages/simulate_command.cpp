#include "stages/simulate_command.hpp"

#include "stages/design_simulation.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/input_error.hpp"
#include "core/units.hpp"
#include "mesh/tet_mesh.hpp"
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
    if (eq == std::string::npos || !std::isfinite(kpa)) bad(d, "--pressure", fmt::format("'{}': expected FIBER=kPa", item));
    const Fiber* f = fiber(name);
    if (!f) bad(d, "--pressure", fmt::format("no [[fiber]] named \"{}\"", name));
    if (kpa < 0 || kpa * units::kPa > d.muscle.max_pressure)
      bad(d, "--pressure", fmt::format("{} kPa for {} is outside [0, {}] kPa ([muscle].max_pressure)", kpa, name,
                                       d.muscle.max_pressure / units::kPa));
    if (std::any_of(out.begin(), out.end(), [&](const Actuation& a) { return a.fiber == name; }))
      bad(d, "--pressure", fmt::format("{} is given twice", name));
    out.push_back({name, f->points, f->tangents, kpa * units::kPa});
  }
  return out;
}

} // namespace

SimulateResult simulate(const Design& d, const Runner& runner, const fs::path& build_dir, const SimulateRequest& request,
                        const ProgressFactory& progress)
{
  if (!request.target.empty() && !request.pressures.empty())
    bad(d, "--target", "give either --target or --pressure, not both");
  const Target* target = nullptr;
  for (const Target& t : d.targets)
    if (t.name == request.target) target = &t;
  if (!request.target.empty() && !target) bad(d, "--target", fmt::format("no [[target]] named \"{}\"", request.target));
  if (target && target->kind == TargetKind::surface)
    bad(d, "--target", fmt::format("target \"{}\" is a deformed surface, not a load: nothing to simulate", target->name));
  std::vector<Actuation> actuations = requested_actuations(d, request);
  if (target && target->kind == TargetKind::fibers) actuations = target_actuations(d, *target);

  runner.make(d, {build_dir, {"mesh"}, false}, progress);
  const TetMesh mesh = load_tet_mesh(build_dir / "mesh" / "body.tetmesh");
  Simulation sim(mesh, simulation_options(d, mesh));
  if (target && target->kind == TargetKind::forces) sim.add_energy(std::make_unique<ExternalForces>(target_forces(d, *target, sim)));

  const MuscleModel model(d.muscle.model);
  const std::vector<const MuscleEnergy*> muscles = add_muscles(sim, d, model, actuations);

  SimulateResult result;
  result.name = target ? target->name : "pressures";
  Eigen::VectorXd x = sim.rest();
  std::unique_ptr<Progress> reporter = progress ? progress("simulate") : nullptr;
  NullProgress silent;
  result.summary = sim.solve(x, reporter ? *reporter : silent);
  if (!result.summary.converged)
    throw std::runtime_error(fmt::format("the simulation did not reach equilibrium: {} ({})", result.summary.brief(),
                                         result.summary.message));
  result.max_displacement = (sim.deformed_nodes(x) - mesh.nodes).rowwise().norm().maxCoeff();
  if (const auto* mls = dynamic_cast<const MlsBasis*>(&sim.basis()); mls && mls->conditioning().widened > 0) {
    const MlsConditioning c = mls->conditioning();
    result.conditioning = fmt::format("MLS radius widened at {} points (too few or co-planar nodes), e.g. at {}, up to "
                                      "{:.3g} mm; consider a finer mesh there or a larger [sim] mls_radius",
                                      c.widened, format_mm(c.example), c.largest_radius / units::mm);
  }
  result.vtu = build_dir / "simulate" / fmt::format("deformed-{}.vtu", result.name);
  write_deformed(result.vtu, sim, x, muscles,
                 LameParameters::from_young_poisson(d.material.youngs_modulus, d.material.poisson_ratio));
  return result;
}

} // namespace fibermold
