#include "pipeline/collide_stage.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

#include "core/atomic_file.hpp"
#include "core/input_error.hpp"
#include "core/units.hpp"
#include "optimize/collision_resolution.hpp"
#include "pipeline/design_simulation.hpp"
#include "pipeline/fibers_file.hpp"
#include "pipeline/routing_evaluation.hpp"

namespace fibermold {

namespace {

using Json = nlohmann::ordered_json;

Json vec_mm(const Eigen::Vector3d& v) { return {v.x() / units::mm, v.y() / units::mm, v.z() / units::mm}; }

Json collisions_json(const std::vector<Contact>& contacts, const std::vector<Route>& routes)
{
  Json out = Json::array();
  for (const Contact& c : contacts)
    out.push_back({{"between", c.with_skin() ? Json{routes[c.a].name, "skin"} : Json{routes[c.a].name, routes[c.b].name}},
                   {"clearance_mm", c.clearance / units::mm},
                   {"at_mm", vec_mm(c.point_a)}});
  return out;
}

/// How far each control point and tangent moved, per fiber (mm).
Json moves_json(const std::vector<Route>& before, const std::vector<Route>& after)
{
  Json out = Json::object();
  for (std::size_t f = 0; f < before.size(); ++f) {
    Json points = Json::array(), tangents = Json::array();
    for (std::size_t k = 0; k < before[f].points.size(); ++k) {
      points.push_back((after[f].points[k] - before[f].points[k]).norm() / units::mm);
      tangents.push_back((after[f].tangents[k] - before[f].tangents[k]).norm() / units::mm);
    }
    out[before[f].name] = {{"points", points}, {"tangents", tangents}};
  }
  return out;
}

/// A centre line outside the body is a routing error, not a collision: refused rather than pulled in.
void check_inside(const Design& d, const FiberClearance& measure, const std::vector<Route>& routes)
{
  const FiberClearance::Lines lines = measure.lines(routes);
  for (const Contact& c : measure.contacts(lines, -measure.radius()))
    if (c.with_skin())
      throw InputError(Diagnostic{d.file, 0, 0, fmt::format("[fiber.{}]", routes[c.a].name),
                                  fmt::format("the fiber (as routed in optimize/fibers.json) leaves the body at {}",
                                              format_mm(c.point_a))});
}

/// Every target simulated under the routing before and after; deformed-<target>.vtu of the latter.
Json resimulate(StageContext& ctx, const FibersFile& fibers, const Routing& resolved, bool changed)
{
  DesignRouting dr(ctx);
  RoutingProblem& problem = dr.start(fibers.routing);
  Json out = Json::object();
  for (int t = 0; t < problem.num_targets(); ++t) {
    const std::string& name = dr.target_names[t];
    ctx.progress.checkpoint(0.3 + 0.7 * t / problem.num_targets(), "simulating target " + name);
    const Eigen::VectorXd x_before = problem.equilibrium(fibers.routing, t);
    const Eigen::VectorXd x_after = changed ? problem.equilibrium(resolved, t) : x_before;
    const TargetErrors before = target_errors(problem, dr.mesh, t, x_before);
    const TargetErrors after = target_errors(problem, dr.mesh, t, x_after);
    write_deformed_target(ctx.output_dir / fmt::format("deformed-{}.vtu", name), dr, resolved, t, x_after);
    const double change = before.rmse > 0 ? 100 * (after.rmse - before.rmse) / before.rmse : 0;
    out[name] = {{"before", errors_json(before)}, {"after", errors_json(after)}, {"rmse_change_percent", change}};
    ctx.log.info("target {}: RMSE {:.3f} mm before, {:.3f} mm after ({:+.1f} %); max {:.3f} → {:.3f} mm on the tracking "
                 "curves; surface RMSE {:.3f} → {:.3f} mm",
                 name, before.rmse / units::mm, after.rmse / units::mm, change, before.max / units::mm,
                 after.max / units::mm, before.surface_rmse / units::mm, after.surface_rmse / units::mm);
  }
  return out;
}

} // namespace

void CollideStage::run(StageContext& ctx) const
{
  const Design& d = ctx.design;
  if (d.collide.reoptimize)
    throw InputError(Diagnostic{d.file, 0, 0, "[collide].reoptimize",
                                "optimizing again with the clearance as a barrier is not available yet; remove the key"});
  const FibersFile fibers = read_fibers_json(ctx.upstream("optimize", "fibers.json"));
  const TetMesh mesh = load_tet_mesh(ctx.upstream("mesh", "body.tetmesh"));
  const SurfaceDistance skin(mesh.nodes, mesh.boundary_faces);

  ctx.progress.update(0.05, "measuring clearances");
  const FiberClearance measure(skin, fibers.routing.routes, d.muscle.model.diameter / 2, d.collide.clearance,
                               d.collide.samples_per_length);
  check_inside(d, measure, fibers.routing.routes);
  ResolutionSettings settings;
  settings.clearance = d.collide.clearance;
  settings.smoothness = d.collide.smoothness;
  const CollisionResolution r = resolve_collisions(measure, fibers.routing.routes, settings);
  for (const Contact& c : r.collided)
    ctx.log.info("{} {}: clearance {:.2f} mm at {}", c.with_skin() ? "fiber" : "fibers",
                 c.with_skin() ? fibers.routing.routes[c.a].name + " and the skin"
                               : fibers.routing.routes[c.a].name + " and " + fibers.routing.routes[c.b].name,
                 c.clearance / units::mm, format_mm(c.point_a));
  if (r.changed)
    ctx.log.info("resolved in {} rounds: the smallest clearance went from {:.3f} mm to {:.3f} mm", r.iterations,
                 r.before / units::mm, r.after / units::mm);
  else
    ctx.log.info("every clearance holds (the smallest is {:.3f} mm): the routing is unchanged", r.before / units::mm);

  FibersFile out = fibers;
  out.routing.routes = r.routes;
  Json report{{"clearance_mm", d.collide.clearance / units::mm},
              {"changed", r.changed},
              {"rounds", r.iterations},
              {"smallest_clearance_mm", {{"before", r.before / units::mm}, {"after", r.after / units::mm}}},
              {"collisions", collisions_json(r.collided, fibers.routing.routes)},
              {"moves_mm", moves_json(fibers.routing.routes, r.routes)}};
  if (fibers.optimized && !d.targets.empty() && !d.tracking_curves.empty()) {
    report["targets"] = resimulate(ctx, fibers, out.routing, r.changed);
  } else {
    report["targets"] = nullptr;
    ctx.log.info("the routing was not optimized: nothing to compare against the targets");
  }
  write_file_atomic(ctx.output_dir / "fibers.json", fibers_json(out));
  write_file_atomic(ctx.output_dir / "report.json", report.dump(2) + "\n");
}

} // namespace fibermold
