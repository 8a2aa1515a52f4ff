#include "stages/targets_stage.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <set>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

#include "core/array_file.hpp"
#include "core/atomic_file.hpp"
#include "core/input_error.hpp"
#include "core/json_file.hpp"
#include "core/units.hpp"
#include "mesh/surface_import.hpp"
#include "mesh/surface_places.hpp"
#include "sim/external_forces.hpp"
#include "stages/design_simulation.hpp"
#include "stages/target_poses.hpp"

namespace fibermold {

namespace {

using Triangle = std::array<int, 3>;

/// Faces as rotation-normalised node triples, to compare connectivity whatever the starting corner.
std::set<Triangle> face_set(const Eigen::MatrixX3i& faces)
{
  std::set<Triangle> out;
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    Triangle t{faces(f, 0), faces(f, 1), faces(f, 2)};
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
    out.insert(t);
  }
  return out;
}

/// Where the surface nodes go under a `kind = "surface"` target: a deformed copy of the body's
/// input surface, carried to the mesh through each node's place on it.
std::vector<std::pair<int, Eigen::Vector3d>> target_surface(const Design& d, const Target& t, const TetMesh& mesh)
{
  const SurfaceMesh s = read_target_surface(d, t, mesh.surface_to_node.size(), mesh.surface_faces);
  return carried_surface(mesh, s.vertices);
}

struct Solved {
  Eigen::VectorXd x;
  NewtonSummary summary;
  double held_error = 0; ///< surface and pose targets: largest distance of a prescribed node from its place, m
  std::vector<PosedRegion> poses;
};

/// Holds `moved` nodes at places(s) for s = 1/steps, 2/steps, …, 1, each solve starting from the
/// last: a target far from the rest shape reached in steps, on one simulation (one factorization).
void solve_in_steps(Simulation& sim, Solved& out, const std::vector<int>& moved, int steps,
                    const std::function<std::vector<Eigen::Vector3d>(double)>& places, Progress& progress)
{
  out.x = sim.rest();
  std::vector<Eigen::Vector3d> at;
  for (int step = 1; step <= steps; ++step) {
    at = places(static_cast<double>(step) / steps);
    sim.move_nodes(at);
    out.summary = sim.solve(out.x, progress);
    if (!out.summary.converged) return;
  }
  const Eigen::MatrixX3d reached = sim.deformed_nodes(out.x);
  for (std::size_t k = 0; k < moved.size(); ++k)
    out.held_error = std::max(out.held_error, (reached.row(moved[k]).transpose() - at[k]).norm());
}

/// Equilibrium of the body for one target; surface and pose targets are reached in steps so that
/// each Newton solve starts close to its answer.
Solved solve_target(const Design& d, const Target& t, const TetMesh& mesh, const MuscleModel& model, StageContext& ctx,
                    std::vector<const MuscleEnergy*>& muscles, Eigen::MatrixX3d& deformed,
                    std::unique_ptr<Simulation>& sim)
{
  if (t.strain_penalty > 0)
    throw InputError(design_problem(d, fmt::format("[target.{}].strain_penalty", t.name),
                                    "the large-strain penalty is not available yet; remove the key"));
  Solved out;
  if (t.kind == TargetKind::surface) {
    const auto moved = target_surface(d, t, mesh);
    SimulationOptions o = simulation_options(d, mesh, false); // the whole surface is prescribed
    o.gravity = Eigen::Vector3d::Zero();
    o.moved_nodes = moved;
    sim = std::make_unique<Simulation>(mesh, o);
    std::vector<int> nodes;
    for (const auto& [node, position] : moved) nodes.push_back(node);
    solve_in_steps(
        *sim, out, nodes, 4,
        [&](double s) {
          std::vector<Eigen::Vector3d> at;
          for (const auto& [node, position] : moved) {
            const Eigen::Vector3d rest = mesh.nodes.row(node).transpose();
            at.push_back(rest + (position - rest) * s);
          }
          return at;
        },
        ctx.progress);
  } else if (t.kind == TargetKind::pose) {
    out.poses = target_poses(d, t, mesh);
    SimulationOptions o = simulation_options(d, mesh); // under gravity, held by [[fixed]]
    std::vector<int> nodes;
    double largest_angle = 0;
    for (const PosedRegion& r : out.poses) {
      for (int n : r.nodes) {
        nodes.push_back(n);
        o.moved_nodes.emplace_back(n, mesh.nodes.row(n).transpose());
      }
      largest_angle = std::max(largest_angle, std::abs(r.angle));
    }
    sim = std::make_unique<Simulation>(mesh, o);
    // A step per 10° of the largest turn, at least 4.
    const int steps = std::max(4, static_cast<int>(std::ceil(largest_angle / (10 * units::degree))));
    solve_in_steps(
        *sim, out, nodes, steps,
        [&](double s) {
          std::vector<Eigen::Vector3d> at;
          for (const PosedRegion& r : out.poses) {
            const RigidMotion m = r.at(s);
            for (int n : r.nodes) at.push_back(m.apply(mesh.nodes.row(n).transpose()));
          }
          return at;
        },
        ctx.progress);
  } else {
    sim = std::make_unique<Simulation>(mesh, simulation_options(d, mesh));
    if (t.kind == TargetKind::forces) sim->add_energy(std::make_unique<ExternalForces>(target_forces(d, t, *sim)));
    if (t.kind == TargetKind::fibers) muscles = add_muscles(*sim, d, model, target_actuations(d, t));
    out.x = sim->rest();
    out.summary = sim->solve(out.x, ctx.progress);
  }
  if (!out.summary.converged)
    throw std::runtime_error(fmt::format("target {}: the simulation did not reach equilibrium: {} ({})", t.name,
                                         out.summary.brief(), out.summary.message));
  deformed = sim->deformed_nodes(out.x);
  return out;
}

} // namespace

SurfaceMesh read_target_surface(const Design& d, const Target& t, Eigen::Index vertices, const Eigen::MatrixX3i& faces)
{
  const std::string key = fmt::format("[target.{}].surface", t.name);
  const SurfaceMesh s = import_surface(t.surface, d.design.surface_scale);
  if (s.num_vertices() != vertices)
    throw InputError(design_problem(d, key,
                                    fmt::format("{} has {} vertices, the body's surface {}: a target surface must be a "
                                                "deformed copy of the body's surface (same vertices, same order)",
                                                t.surface.filename().string(), s.num_vertices(), vertices)));
  if (face_set(s.faces) != face_set(faces))
    throw InputError(
        design_problem(d, key,
                       fmt::format("{} connects its vertices differently from the body's surface: the vertex "
                                   "order changed (export it from the same mesh without reordering)",
                                   t.surface.filename().string())));
  return s;
}

std::vector<std::string> TargetsStage::design_keys_used(const Design& d) const
{
  std::vector<std::string> keys = design_keys();
  if (std::none_of(d.targets.begin(), d.targets.end(), [](const Target& t) { return t.kind == TargetKind::fibers; }))
    std::erase_if(keys, [](const std::string& k) { return k == "fiber" || k == "muscle"; });
  return keys;
}

std::vector<std::filesystem::path> TargetsStage::input_files(const Design& d) const
{
  std::vector<std::filesystem::path> files;
  for (const Target& t : d.targets)
    if (t.kind == TargetKind::surface)
      for (const auto& f : surface_files(t.surface)) files.push_back(f);
  return files;
}

void TargetsStage::run(StageContext& ctx) const
{
  const Design& d = ctx.design;
  const TetMesh mesh = load_tet_mesh(ctx.upstream("mesh", "body.tetmesh"));
  const MuscleModel model(d.muscle.model);
  const LameParameters lame = LameParameters::from_young_poisson(d.material.youngs_modulus, d.material.poisson_ratio);
  nlohmann::ordered_json report = nlohmann::ordered_json::object();
  for (std::size_t k = 0; k < d.targets.size(); ++k) {
    const Target& t = d.targets[k];
    ctx.progress.checkpoint(static_cast<double>(k) / d.targets.size(), "target " + t.name);
    std::vector<const MuscleEnergy*> muscles;
    Eigen::MatrixX3d deformed;
    std::unique_ptr<Simulation> sim;
    const Solved solved = solve_target(d, t, mesh, model, ctx, muscles, deformed, sim);
    save_array(ctx.output_dir / (t.name + ".positions"), "positions", solved.x);
    nlohmann::ordered_json nodes = nlohmann::ordered_json::array(); // for report.html: the target beside the robot
    for (Eigen::Index i = 0; i < deformed.rows(); ++i)
      nodes.push_back({deformed(i, 0) / units::mm, deformed(i, 1) / units::mm, deformed(i, 2) / units::mm});
    write_json_atomic(ctx.output_dir / (t.name + ".json"),
                      nlohmann::ordered_json{{"target", t.name}, {"nodes_mm", std::move(nodes)}});
    write_deformed(ctx.output_dir / (t.name + ".vtu"), *sim, solved.x, muscles, lame);
    const double max_mm = (deformed - mesh.nodes).rowwise().norm().maxCoeff() / units::mm;
    report[t.name] = {{"kind", choice_name(t.kind)},
                      {"max_displacement_mm", max_mm},
                      {"newton_iterations", solved.summary.iterations},
                      {"residual_N", solved.summary.residual}};
    if (t.kind == TargetKind::surface) report[t.name]["max_surface_error_mm"] = solved.held_error / units::mm;
    if (t.kind == TargetKind::pose) report[t.name]["max_pose_error_mm"] = solved.held_error / units::mm;
    ctx.log.info("target {} ({}): max displacement {:.3f} mm; {}", t.name, choice_name(t.kind), max_mm,
                 solved.summary.brief());
    nlohmann::ordered_json poses = nlohmann::ordered_json::array();
    for (const ReachedPose& p : reached_poses(d, t, *sim, solved.x, solved.poses)) {
      poses.push_back(pose_report(p));
      ctx.log.info("  {}: moved {:.2f} mm, turned {:.2f}° about ({:.3f}, {:.3f}, {:.3f})", p.place,
                   p.displacement.norm() / units::mm, p.motion.angle() / units::degree, p.motion.axis().x(),
                   p.motion.axis().y(), p.motion.axis().z());
    }
    report[t.name]["poses"] = std::move(poses);
  }
  write_json_atomic(ctx.output_dir / "report.json", report);
}

} // namespace fibermold
