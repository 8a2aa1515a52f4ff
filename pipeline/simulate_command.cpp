#include "pipeline/simulate_command.hpp"

#include <cmath>

#include <Eigen/LU>
#include <fmt/format.h>

#include "core/input_error.hpp"
#include "core/units.hpp"
#include "export/vtu_writer.hpp"
#include "mesh/tet_mesh.hpp"
#include "sim/external_forces.hpp"
#include "sim/fem_basis.hpp"
#include "sim/mls_basis.hpp"
#include "sim/muscle_energy.hpp"
#include "sim/neo_hookean.hpp"
#include "sim/simulation.hpp"

namespace fibermold {

namespace fs = std::filesystem;

namespace {

[[noreturn]] void bad(const Design& d, const std::string& key, const std::string& message)
{
  throw InputError(Diagnostic{d.file, 0, 0, key, message});
}

std::string mm(const Eigen::Vector3d& p)
{
  return fmt::format("({:.1f}, {:.1f}, {:.1f}) mm", p.x() / units::mm, p.y() / units::mm, p.z() / units::mm);
}

/// The mesh nodes a region (box or surface vertices) selects.
std::vector<int> region_nodes(const Region& r, const TetMesh& mesh, const Design& d, const std::string& key)
{
  std::vector<int> nodes;
  if (r.box) nodes = nodes_in_box(mesh.nodes, (*r.box)[0], (*r.box)[1]);
  for (int v : r.vertices) {
    if (v >= mesh.surface_to_node.size())
      bad(d, key, fmt::format("vertex {} does not exist: the surface has {} vertices", v, mesh.surface_to_node.size()));
    nodes.push_back(mesh.surface_to_node(v));
  }
  return nodes;
}

SimulationOptions simulation_options(const Design& d, const TetMesh& mesh)
{
  SimulationOptions o;
  o.basis = d.sim.basis;
  o.mls_radius = d.sim.mls_radius;
  o.quadrature_points = d.sim.quadrature_points;
  o.youngs_modulus = d.material.youngs_modulus;
  o.poisson_ratio = d.material.poisson_ratio;
  o.density = d.material.density;
  o.gravity = d.material.gravity;
  if (d.fixed.empty())
    bad(d, "[[fixed]]", "the body is held nowhere: add a [[fixed]] region (a free body under load has no equilibrium)");
  for (const FixedRegion& f : d.fixed) {
    const std::string key = fmt::format("[fixed.{}]", f.name);
    std::vector<int> nodes = region_nodes(f.region, mesh, d, key);
    if (nodes.empty()) {
      const Eigen::Vector3d lo = mesh.nodes.colwise().minCoeff(), hi = mesh.nodes.colwise().maxCoeff();
      bad(d, key, fmt::format("holds no node of the mesh, which spans {} to {}", mm(lo), mm(hi)));
    }
    o.fixed_nodes.push_back(std::move(nodes));
  }
  return o;
}

/// The nodal forces of a forces target's loads.
Eigen::VectorXd target_forces(const Design& d, const Target& t, const Simulation& sim)
{
  const TetMesh& mesh = sim.mesh();
  Eigen::VectorXd f = Eigen::VectorXd::Zero(3 * mesh.nodes.rows());
  for (std::size_t i = 0; i < t.loads.size(); ++i) {
    const Load& load = t.loads[i];
    const std::string key = fmt::format("[target.{}].load[{}]", t.name, i + 1);
    if (load.region.point) {
      f += point_force(sim.basis().at(*load.region.point, 0), mesh.nodes.rows(), *load.force);
      continue;
    }
    const std::vector<int> nodes = region_nodes(load.region, mesh, d, key);
    if (nodes.empty()) bad(d, key, "the load's region holds no node of the mesh");
    if (load.force) f += region_force(nodes, sim.masses(), mesh.nodes, *load.force);
    if (load.torque) f += region_torque(nodes, sim.masses(), mesh.nodes, *load.torque);
  }
  return f;
}

/// Refuses a fiber that leaves the body: every segment end must lie in a tet (within 1e-6 of it).
void require_inside(const Design& d, const std::string& fiber, const FemBasis& locator, const HermiteSpline& spline,
                    const FiberSegments& segments)
{
  for (double t : segments.t) {
    const Eigen::Vector3d p = spline.position(t);
    if (locator.barycentric(locator.locate(p), p).minCoeff() < -1e-6)
      bad(d, fmt::format("[fiber.{}]", fiber), fmt::format("the fiber leaves the body at {}", mm(p)));
  }
}

struct Actuation {
  std::string fiber;
  std::vector<Eigen::Vector3d> points, tangents;
  double pressure;
};

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
    out.push_back({name, f->points, f->tangents, kpa * units::kPa});
  }
  return out;
}

/// VTU of the deformed body (points at x(X_i), displacement in mm, von Mises stress in kPa at each
/// tet's centre) with the fibers as deformed polylines.
void write_deformed(const fs::path& path, const Simulation& sim, const Eigen::VectorXd& x,
                    const std::vector<const MuscleEnergy*>& muscles, const std::vector<HermiteSpline>& splines,
                    const LameParameters& lame)
{
  const TetMesh& mesh = sim.mesh();
  const Eigen::MatrixX3d deformed = sim.deformed_nodes(x);
  std::vector<Eigen::Vector3d> rest_points, points;
  for (Eigen::Index i = 0; i < mesh.nodes.rows(); ++i) {
    rest_points.push_back(mesh.nodes.row(i).transpose());
    points.push_back(deformed.row(i).transpose());
  }
  std::vector<std::vector<int>> lines;
  for (std::size_t m = 0; m < muscles.size(); ++m) {
    std::vector<int> line;
    for (double t : muscles[m]->segments().t) {
      const Eigen::Vector3d X = splines[m].position(t);
      line.push_back(static_cast<int>(points.size()));
      rest_points.push_back(X);
      points.push_back(sim.basis().at(X, 0).position(x));
    }
    lines.push_back(std::move(line));
  }
  Eigen::MatrixX3d P(static_cast<Eigen::Index>(points.size()), 3);
  Eigen::MatrixXd u(P.rows(), 3);
  for (Eigen::Index i = 0; i < P.rows(); ++i) {
    P.row(i) = points[i].transpose();
    u.row(i) = (points[i] - rest_points[i]).transpose() / units::mm;
  }
  VtuGrid grid(P);
  grid.add_cells(mesh.tets, mesh.nodes_per_tet() == 10 ? VtkCell::quadratic_tetra : VtkCell::tetra);
  for (const auto& line : lines) grid.add_cell(line, VtkCell::poly_line);
  Eigen::MatrixXd von_mises = Eigen::MatrixXd::Zero(grid.num_cells(), 1);
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (int k = 0; k < 4; ++k) c += mesh.nodes.row(mesh.tets(t, k)).transpose() / 4;
    const Eigen::Matrix3d F = sim.basis().at(c, 1, t).deformation_gradient(x);
    const Eigen::Matrix3d sigma = neo_hookean_stress(F, lame) * F.transpose() / F.determinant();  // Cauchy
    const Eigen::Matrix3d s = sigma - sigma.trace() / 3 * Eigen::Matrix3d::Identity();
    von_mises(t, 0) = std::sqrt(1.5 * s.squaredNorm()) / units::kPa;
  }
  grid.add_point_field("displacement_mm", u);
  grid.add_cell_field("von_mises_kPa", von_mises);
  grid.write(path);
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
  if (target && target->kind == "surface")
    bad(d, "--target", fmt::format("target \"{}\" is a deformed surface, not a load: nothing to simulate", target->name));
  std::vector<Actuation> actuations = requested_actuations(d, request);
  if (target && target->kind == "fibers")
    for (const FiberActuation& a : target->fibers) {
      const Fiber* f = nullptr;
      for (const Fiber& fb : d.fibers)
        if (fb.name == a.name) f = &fb;
      actuations.push_back({a.name, a.points.empty() ? f->points : a.points, a.points.empty() ? f->tangents : std::vector<Eigen::Vector3d>{},
                            a.pressure});
    }

  runner.make(d, {build_dir, {"mesh"}, false}, progress);
  const TetMesh mesh = load_tet_mesh(build_dir / "mesh" / "body.tetmesh");
  Simulation sim(mesh, simulation_options(d, mesh));
  if (target && target->kind == "forces") sim.add_energy(std::make_unique<ExternalForces>(target_forces(d, *target, sim)));

  const MuscleModel model(d.muscle.model);
  const FemBasis locator(mesh);
  std::vector<const MuscleEnergy*> muscles;
  std::vector<HermiteSpline> splines;
  for (const Actuation& a : actuations) {
    splines.emplace_back(a.points, a.tangents);
    const int count = std::max(1, static_cast<int>(std::ceil(splines.back().length() * d.muscle.segments_per_length)));
    std::vector<double> t = segment_parameters(splines.back(), count);
    require_inside(d, a.fiber, locator, splines.back(), segments_at(splines.back(), t));
    auto muscle = std::make_unique<MuscleEnergy>(sim.basis(), model, splines.back(), std::move(t), a.pressure);
    muscles.push_back(muscle.get());
    sim.add_energy(std::move(muscle));
  }

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
                                      c.widened, mm(c.example), c.largest_radius / units::mm);
  }
  result.vtu = build_dir / "simulate" / fmt::format("deformed-{}.vtu", result.name);
  write_deformed(result.vtu, sim, x, muscles, splines,
                 LameParameters::from_young_poisson(d.material.youngs_modulus, d.material.poisson_ratio));
  return result;
}

} // namespace fibermold
