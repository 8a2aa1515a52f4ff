#include "stages/collide_stage.hpp"

#include <array>
#include <cmath>
#include <memory>
#include <optional>
#include <string_view>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

#include "core/atomic_file.hpp"
#include "core/input_error.hpp"
#include "core/json_file.hpp"
#include "core/units.hpp"
#include "optimize/clearance_barrier.hpp"
#include "optimize/collision_resolution.hpp"
#include "optimize/full_turn_search.hpp"
#include "optimize/optimization_ending.hpp"
#include "stages/design_simulation.hpp"
#include "stages/fibers_file.hpp"
#include "stages/routing_evaluation.hpp"
#include "stages/target_poses.hpp"

namespace fibermold {

namespace {

using Json = nlohmann::ordered_json;

constexpr double kReportReach = 10e-3; // m: clearances are reported up to this much above the asked one
/// What to try where moving fibers apart bent one too tightly or pushed it to the skin.
constexpr const char* kSmoothnessAdvice = "; or raise [collide] smoothness, which spreads a move along the fiber";

/// The smallest clearance (mm) among fibers and skin, before and after; a value more than
/// kReportReach above the clearance asked for is not measured, and left out.
Json smallest_json(const FiberClearance& measure, const std::vector<Route>& before, const std::vector<Route>& after,
                   double clearance)
{
  Json out = Json::object();
  for (const auto& [name, routes] : {std::pair{"before", &before}, std::pair{"after", &after}})
    if (const double c = smallest_clearance(measure.contacts(*routes, clearance + kReportReach)); std::isfinite(c))
      out[name] = c / units::mm;
  out["measured_up_to"] = (clearance + kReportReach) / units::mm;
  return out;
}

Json vec_mm(const Eigen::Vector3d& v) { return {v.x() / units::mm, v.y() / units::mm, v.z() / units::mm}; }

Json collisions_json(const std::vector<Contact>& contacts, const std::vector<Route>& routes)
{
  Json out = Json::array();
  for (const Contact& c : contacts)
    out.push_back(
        {{"between", c.with_skin() ? Json{routes[c.a].name, "skin"} : Json{routes[c.a].name, routes[c.b].name}},
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

/// A centre line outside the body is a routing error, not a collision: refused rather than pulled
/// in; the design's when the routes are hand-made (exit 2), the optimizer's otherwise (exit 1).
void check_inside(const Design& d, const FiberClearance& measure, const FibersFile& fibers)
{
  const std::vector<Route>& routes = fibers.routing.routes;
  for (const Contact& c : measure.contacts(measure.lines(routes), -measure.radius())) {
    if (!c.with_skin()) continue;
    const std::string what =
        fmt::format("the fiber (as routed in optimize/fibers.json) leaves the body at {}", format_mm(c.point_a));
    if (fibers.optimized) throw std::runtime_error(fmt::format("fiber {}: {}", routes[c.a].name, what));
    throw InputError(design_problem(d, fmt::format("[fiber.{}]", routes[c.a].name), what));
  }
}

/// The errors of every target under routing r, each equilibrium found from rest.
std::vector<TargetErrors> errors_under(RoutingProblem& problem, DesignRouting& dr, const Routing& r,
                                       std::vector<Eigen::VectorXd>* states = nullptr)
{
  problem.forget_states();
  std::vector<TargetErrors> out;
  for (int t = 0; t < problem.num_targets(); ++t) {
    const Eigen::VectorXd x = problem.equilibrium(r, t);
    out.push_back(target_errors(problem, dr.mesh, t, x));
    if (states) states->push_back(x);
  }
  return out;
}

/// require_bend_radius (routing_evaluation.hpp) on routes collide moved, as the stage's failure: the
/// fiber, where, by how much and what to do.
void require_bend_radius_after_moving(const Design& d, const std::vector<Route>& routes, std::string_view whose)
{
  try {
    require_bend_radius(d, routes, whose, false);
  } catch (const InputError& e) {
    const Diagnostic& said = e.diagnostics().front();
    throw std::runtime_error(fmt::format("{}: {}{}", said.key, said.message, kSmoothnessAdvice));
  }
}

/// Optimizing again starts from the routing moved apart, which moving may have bent under the
/// muscle's smallest radius or pushed against the skin, walls of the optimizer's: the fiber, where
/// and what to do, rather than the optimizer's "not finite at the starting point".
void require_optimizable(const Design& d, const RoutingProblem& problem, const Routing& moved)
{
  require_bend_radius_after_moving(d, moved.routes, "the route as collide moved it apart");
  double distance = 0;
  Eigen::Vector3d where;
  if (const int f = problem.skin_violation(moved, distance, where); f >= 0)
    throw std::runtime_error(fmt::format("[fiber.{}]: the route as collide moved it apart comes within {:.2f} mm of "
                                         "the skin at {}, under the skin distance the optimizer keeps{}",
                                         moved.routes[f].name, distance / units::mm, format_mm(where),
                                         kSmoothnessAdvice));
  ExitShortfall e;
  if (const int g = problem.exit_violation(moved, e); g >= 0)
    throw std::runtime_error(fmt::format("[fiber.{}]: the route as collide moved it apart leaves the body along the "
                                         "skin at {}, {:.2f} mm from it, {:.1f} mm from its end, under the {:.2f} mm "
                                         "the optimizer keeps there{}",
                                         moved.routes[g].name, format_mm(e.where), e.distance / units::mm,
                                         e.from_end / units::mm, e.required / units::mm, kSmoothnessAdvice));
}

/// Optimizes again from the resolved routing with the clearance between fibers as a barrier
/// (the skin barrier keeps them off the skin), as the paper suggests (section V-B).
Routing reoptimize(StageContext& ctx, RoutingProblem& problem, const FiberClearance& measure, const Routing& resolved)
{
  const Design& d = ctx.design;
  require_optimizable(d, problem, resolved);
  const ClearanceBarrier barrier(measure, resolved.routes, d.collide.clearance, d.muscle.model.radius());
  problem.set_base(resolved);
  problem.set_clearance_barrier(&barrier, kClearanceBarrierWeight);
  const MinimizerOptions o = minimizer_options(d);
  const RoutingCallback on_iteration = [&](int, const MinimizerIteration& it, const RoutingTerms& terms) {
    const std::string what = fmt::format("optimizing again, iteration {}: objective {:.4g} (distance {:.4g}, clearance "
                                         "barrier {:.3g})",
                                         it.iteration, terms.total, terms.distance, terms.clearance);
    ctx.progress.update(0.2 + 0.6 * it.iteration / std::max(1, o.max_iterations), what);
    ctx.log.info("{}", what);
  };
  const RoutingResult r =
      optimize_routing(problem, Strategy::simultaneous, o, on_iteration, ctx.progress, actuator_mask(d));
  problem.set_clearance_barrier(nullptr, 0);
  if (r.interrupted) throw Interrupted();
  ctx.log.info("optimized again: {} after {} iterations", r.message, r.iterations);
  return r.routing;
}

/// Resolves the clearances of the routing and says what it found.
CollisionResolution resolve(StageContext& ctx, const FiberClearance& measure, const FibersFile& fibers)
{
  const Design& d = ctx.design;
  const std::vector<Route>& routes = fibers.routing.routes;
  check_inside(d, measure, fibers);
  ResolutionSettings settings;
  settings.clearance = d.collide.clearance;
  // Optimizing again needs room inside its barriers, which are infinite at the clearance itself.
  settings.room = d.collide.reoptimize ? kBarrierRoom : 0;
  settings.smoothness = d.collide.smoothness;
  CollisionResolution r = resolve_collisions(measure, routes, settings);
  for (const Contact& c : r.collided)
    ctx.log.info("{}: clearance {:.2f} mm at {}",
                 c.with_skin() ? "fiber " + routes[c.a].name + " and the skin"
                               : "fibers " + routes[c.a].name + " and " + routes[c.b].name,
                 c.clearance / units::mm, format_mm(c.point_a));
  if (r.changed)
    ctx.log.info("resolved in {} rounds: the smallest clearance went from {:.3f} mm to {:.3f} mm", r.iterations,
                 r.before / units::mm, r.after / units::mm);
  else
    ctx.log.info("every clearance holds (the smallest is {:.3f} mm): the routing is unchanged", r.before / units::mm);
  return r;
}

/// The body with its silicone's Young's modulus scaled by `factor`, and the routing problem over it
/// with its muscle segments placed as in `segments`, to solve the final routing's targets again.
struct ScaledStiffness {
  std::unique_ptr<Simulation> sim;
  std::unique_ptr<RoutingProblem> problem;
  ScaledStiffness(const DesignRouting& dr, const Routing& segments, double factor)
  {
    SimulationOptions o = simulation_options(dr.design, dr.mesh);
    o.youngs_modulus *= factor;
    sim = std::make_unique<Simulation>(dr.mesh, o);
    problem = std::make_unique<RoutingProblem>(*sim, dr.model, *dr.skin, dr.targets, dr.curves, segments,
                                               routing_settings(dr.design));
  }
};

/// For pose region `reached` (the i-th of target t's poses) turned short of its angle (under
/// kShortOfTurn of it) under `final`: the pressures that turn it the whole angle, every pressure of the
/// target scaled alike, at most [muscle] max_pressure (full_turn_search.hpp, from its turns with every
/// pressure kSensitivityChange lower and higher, `lower` and `higher`), each solved from rest. The
/// optimizer weighed the turn against the tracking curves' positions: this says what the turn alone
/// would take (a new user's starfish turned 28.0° of 40° at 286 and 288 kPa of 425; 1.42 × turns it
/// 40.0°). None where the turn does not grow with the pressure, or no equilibrium is found.
std::optional<Json> full_turn(StageContext& ctx, DesignRouting& dr, const Routing& final, int t,
                              const std::vector<PosedRegion>& asked, std::size_t i, const ReachedPose& reached,
                              const ReachedPose& lower, const ReachedPose& higher)
{
  if (!reached.asked || reached.asked->angle == 0) return std::nullopt;
  const Eigen::Vector3d axis = reached.asked->axis;
  const double angle = reached.asked->angle, turned = reached.motion.angle_about(axis);
  const Eigen::RowVectorXd p = final.pressures.row(t);
  const double highest = p.maxCoeff();
  if (!(turned / angle < kShortOfTurn) || !(highest > 0)) return std::nullopt;
  const Design& d = ctx.design;
  const Target& target = d.targets[static_cast<std::size_t>(t)];
  ctx.progress.checkpoint(-1,
                          fmt::format("target {}: the pressures that turn {} all the way", target.name, reached.place));
  const auto turn_at = [&](double s) {
    if (s == 1) return turned; // the nominal, solved already (the highest pressure at max_pressure)
    Routing pressed = final;
    pressed.pressures.row(t) *= s;
    dr.problem->forget_states(); // from rest, as the nominal solve
    try {
      return reached_poses(d, target, *dr.sim, dr.problem->equilibrium(pressed, t), asked)[i].motion.angle_about(axis);
    } catch (const Interrupted&) {
      throw;
    } catch (const std::runtime_error& e) {
      ctx.log.warn("target {}: {} at {:.2f} × its pressures, to turn its whole angle: {}", target.name, reached.place,
                   s, e.what());
      throw;
    }
  };
  const std::optional<FullTurn> found =
      full_turn_search(angle, 1 - kSensitivityChange, lower.motion.angle_about(axis), 1 + kSensitivityChange,
                       higher.motion.angle_about(axis), d.muscle.max_pressure / highest, turn_at);
  if (!found) return std::nullopt;
  Json pressures = Json::object(), off = Json::array();
  const ActuatorMask muscles = actuator_mask(d);
  for (Eigen::Index f = 0; f < p.size(); ++f) {
    const std::string& fiber = final.routes[static_cast<std::size_t>(f)].name;
    if (p(f) > 0)
      pressures[fiber] = found->scale * p(f) / units::kPa;
    else if (muscles(t, f))
      off.push_back(fiber);
  }
  return Json{{"pressure_scale", found->scale},
              {"pressures_kPa", std::move(pressures)},
              {"off", std::move(off)},
              {"at_max_pressure", found->at_most},
              {"max_pressure_kPa", d.muscle.max_pressure / units::kPa},
              {"rotation_about_asked_axis_deg", found->turn / units::degree},
              {"reached", found->reached}};
}

/// The robot with every muscle at 0 kPa, under its weight and held as designed: one equilibrium for
/// every target (a target's loads made its shape; the robot does not carry them), what a lab sees of
/// the cast robot before it pressurizes it (a new user's 90 mm finger of Dragon Skin 10 turned its tip
/// 19.3° so, of the 31.9° it turns at its pressure). None without gravity (the body stays at rest) or
/// where no equilibrium is found.
std::optional<Eigen::VectorXd> unpressurized(StageContext& ctx, DesignRouting& dr, const Routing& final)
{
  if (ctx.design.material.gravity.norm() == 0 || dr.problem->num_targets() == 0) return std::nullopt;
  Routing rest = final;
  rest.pressures.setZero();
  try {
    dr.problem->forget_states(); // from rest, as every other solve here
    return dr.problem->equilibrium(rest, 0);
  } catch (const Interrupted&) {
    throw;
  } catch (const std::runtime_error& e) {
    ctx.log.warn("the robot unpressurized, under its weight: {}; its poses have no unpressurized figures", e.what());
    return std::nullopt;
  }
}

/// Target t's poses under `final` in deformation x, each with where it goes under kPoseVariations: the
/// silicone stiffer and softer (`scaled`), every pressure lower and higher, each solved from rest as x
/// was; none where a variation finds no equilibrium. With `rest` (unpressurized()), where each goes
/// with every muscle at 0 kPa.
Json poses_json(StageContext& ctx, DesignRouting& dr, std::array<ScaledStiffness, 2>& scaled, const Routing& final,
                int t, const Eigen::VectorXd& x, const std::optional<Eigen::VectorXd>& rest)
{
  const Design& d = ctx.design;
  const Target& target = d.targets[static_cast<std::size_t>(t)];
  const std::vector<PosedRegion> asked =
      target.kind == TargetKind::pose ? target_poses(d, target, dr.mesh) : std::vector<PosedRegion>{};
  const std::vector<ReachedPose> reached = reached_poses(d, target, *dr.sim, x, asked);
  std::array<std::vector<ReachedPose>, 4> varied;
  try {
    for (int k = 0; k < 2; ++k)
      varied[k] = reached_poses(d, target, *scaled[k].sim, scaled[k].problem->equilibrium(final, t), asked);
    for (int k = 0; k < 2; ++k) {
      Routing pressed = final;
      pressed.pressures *= k == 0 ? 1 - kSensitivityChange : 1 + kSensitivityChange;
      dr.problem->forget_states(); // from rest, as the robot and the nominal solve: one branch of a multi-stable body
      varied[2 + k] = reached_poses(d, target, *dr.sim, dr.problem->equilibrium(pressed, t), asked);
    }
  } catch (const Interrupted&) {
    throw; // a runtime_error too: Ctrl-C stops the stage, not only this target's sensitivity
  } catch (const std::runtime_error& e) {
    ctx.log.warn("target {}: with the silicone or the pressures {:.0f} % off: {}; its poses have no sensitivity",
                 target.name, 100 * kSensitivityChange, e.what());
    varied = {};
  }
  Json poses = Json::array();
  for (std::size_t i = 0; i < reached.size(); ++i)
    poses.push_back(varied[3].empty()
                        ? pose_report(reached[i])
                        : pose_report(reached[i], {varied[0][i], varied[1][i], varied[2][i], varied[3][i]}));
  if (rest) {
    const std::vector<ReachedPose> at_rest = reached_poses(d, target, *dr.sim, *rest, asked);
    for (std::size_t i = 0; i < reached.size(); ++i) {
      const ReachedPose& r = at_rest[i];
      Json& u = poses[i]["unpressurized"] = {{"rotation_deg", r.motion.angle() / units::degree},
                                             {"displacement_mm", r.displacement.norm() / units::mm}};
      if (r.asked) u["rotation_about_asked_axis_deg"] = r.motion.angle_about(r.asked->axis) / units::degree;
    }
  }
  if (!varied[3].empty())
    for (std::size_t i = 0; i < reached.size(); ++i)
      if (auto turn = full_turn(ctx, dr, final, t, asked, i, reached[i], varied[2][i], varied[3][i]))
        poses[i]["full_turn"] = std::move(*turn);
  return poses;
}

/// Every target simulated from rest under the optimized routing and under the final one (optimized
/// again first when asked), into the report; deformed-<target>.vtu of the final one.
void simulate_targets(StageContext& ctx, const FiberClearance& measure, const FibersFile& fibers, bool changed,
                      Routing& final, Json& report)
{
  const Design& d = ctx.design;
  DesignRouting dr(ctx);
  const Routing segments = optimization_start(d, *dr.skin).routing; // the muscle segments as the optimizer had them
  RoutingProblem& problem = dr.start(segments);
  // Progress by the solves from rest, each target's: one under the optimized routing, one under the final
  // one and four with the silicone and the pressures off (on the gripper finger 2.4, 3.0 and 9.7 s, where
  // a 0.85–0.9–1 split said "~1 s left" with 10 s to go); optimizing again, when asked, takes 0.2–0.8.
  const double final_at = changed && d.collide.reoptimize ? 0.8 : 0.25, off_at = final_at + (1 - final_at) / 5;
  ctx.progress.update(0.1, "simulating the targets under the optimized routing");
  // Unchanged (resolve_collisions returns a clear routing bit for bit), the final routing is the optimized one:
  // its solves from rest are these.
  std::vector<Eigen::VectorXd> states;
  const std::vector<TargetErrors> before = errors_under(problem, dr, fibers.routing, changed ? nullptr : &states);
  std::vector<TargetErrors> resolved;
  if (changed && d.collide.reoptimize) {
    resolved = errors_under(problem, dr, final);
    final = reoptimize(ctx, problem, measure, final);
    if (const auto left = measure.contacts(final.routes, d.collide.clearance - 1e-6); !left.empty())
      throw std::runtime_error(fmt::format("optimizing again left {} closer than the clearance at {}",
                                           left.front().with_skin() ? "a fiber and the skin" : "two fibers",
                                           format_mm(left.front().point_a)));
    report["reoptimized"] = true;
    Json& smallest = report["smallest_clearance_mm"];
    smallest.erase("after");
    if (const Json again = smallest_json(measure, final.routes, final.routes, d.collide.clearance);
        again.contains("after"))
      smallest["after"] = again["after"];
  }
  if (changed) ctx.progress.update(final_at, "simulating the targets under the final routing");
  const std::vector<TargetErrors> after = changed ? errors_under(problem, dr, final, &states) : before;
  std::array<ScaledStiffness, 2> scaled{ScaledStiffness(dr, segments, 1 + kSensitivityChange),
                                        ScaledStiffness(dr, segments, 1 - kSensitivityChange)};
  Json targets = Json::object();
  const std::optional<Eigen::VectorXd> rest = unpressurized(ctx, dr, final);
  for (int t = 0; t < problem.num_targets(); ++t) {
    const std::string& name = dr.target_names[t];
    write_deformed_target(ctx.output_dir / fmt::format("deformed-{}.vtu", name), dr, final, t, states[t]);
    write_file_atomic(ctx.output_dir / fmt::format("deformed-{}.json", name), deformed_json(dr, final, t, states[t]));
    const double change = before[t].rmse > 0 ? 100 * (after[t].rmse - before[t].rmse) / before[t].rmse : 0;
    targets[name] = {
        {"before", errors_json(before[t])}, {"after", errors_json(after[t])}, {"rmse_change_percent", change}};
    if (!resolved.empty()) targets[name]["resolved"] = errors_json(resolved[t]);
    // Where the regions and the tracking curves' ends went: what a user measures on the cast robot.
    ctx.progress.update(
        off_at + (1 - off_at) * t / problem.num_targets(),
        fmt::format("target {}: the silicone and the pressures {:.0f} % off", name, 100 * kSensitivityChange));
    targets[name]["poses"] = poses_json(ctx, dr, scaled, final, t, states[t], rest);
    ctx.log.info("target {}: RMSE {:.3f} mm before, {:.3f} mm after ({:+.1f} %); max {:.3f} → {:.3f} mm on the "
                 "tracking curves; surface RMSE {:.3f} → {:.3f} mm",
                 name, before[t].rmse / units::mm, after[t].rmse / units::mm, change, before[t].max / units::mm,
                 after[t].max / units::mm, before[t].surface_rmse / units::mm, after[t].surface_rmse / units::mm);
  }
  report["targets"] = targets;
}

} // namespace

void CollideStage::run(StageContext& ctx) const
{
  const Design& d = ctx.design;
  const FibersFile fibers = read_fibers_json(ctx.upstream("optimize", "fibers.json"));
  const TetMesh mesh = load_tet_mesh(ctx.upstream("mesh", "body.tetmesh"));
  const SurfaceDistance skin(mesh.nodes, mesh.boundary_faces);
  if (fibers.routing.routes.size() != d.fibers.size())
    throw std::runtime_error(fmt::format("optimize/fibers.json has {} fibers, the design {}: run optimize again",
                                         fibers.routing.routes.size(), d.fibers.size()));
  ctx.progress.update(0.05, "measuring clearances");
  // The skin is tested where the optimizer's skin barrier held it, set by the routes it started from.
  const FiberClearance measure =
      design_clearance(d, skin, fibers.routing.routes, optimization_start(d, skin).routing.routes);
  const CollisionResolution r = resolve(ctx, measure, fibers);

  FibersFile out = fibers;
  out.routing.routes = r.routes;
  Json report{{"clearance_mm", d.collide.clearance / units::mm},
              {"changed", r.changed},
              {"rounds", r.iterations},
              {"smallest_clearance_mm", smallest_json(measure, fibers.routing.routes, r.routes, d.collide.clearance)},
              {"collisions", collisions_json(r.collided, fibers.routing.routes)},
              {"reoptimized", false},
              {"targets", Json::object()}};
  if (fibers.optimized && !d.targets.empty() && !d.tracking_curves.empty()) {
    simulate_targets(ctx, measure, fibers, r.changed, out.routing, report);
  } else {
    if (d.collide.reoptimize)
      ctx.log.warn("[collide] reoptimize: the routing was not optimized, so it is not optimized again");
    ctx.log.info("the routing was not optimized: nothing to compare against the targets");
  }
  // Moving fibers apart can bend them: the molds would refuse a route under the muscle's radius.
  require_bend_radius_after_moving(d, out.routing.routes, "the route as collide left it");
  report["min_bend_radius_mm"] = d.muscle.min_bend_radius / units::mm;
  report["bends"] = bends_json(out.routing.routes);
  report["moves_mm"] = moves_json(fibers.routing.routes, out.routing.routes);
  write_file_atomic(ctx.output_dir / "fibers.json", fibers_json(out));
  write_json_atomic(ctx.output_dir / "report.json", report);
}

} // namespace fibermold
