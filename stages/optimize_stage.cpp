#include "stages/optimize_stage.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

#include "core/array_file.hpp"
#include "core/atomic_file.hpp"
#include "core/elapsed.hpp"
#include "core/input_error.hpp"
#include "core/json_file.hpp"
#include "core/units.hpp"
#include "optimize/clearance_barrier.hpp"
#include "optimize/first_guess_comparison.hpp"
#include "optimize/optimization_ending.hpp"
#include "optimize/routing_history.hpp"
#include "optimize/routing_optimizer.hpp"
#include "optimize/several_starts.hpp"
#include "stages/design_mesh.hpp"
#include "stages/design_simulation.hpp"
#include "stages/fibers_file.hpp"
#include "stages/routing_evaluation.hpp"
#include "stages/skin_distance.hpp"
#include "stages/target_poses.hpp"

namespace fibermold {

namespace fs = std::filesystem;

namespace {

using Clock = std::chrono::steady_clock;
/// Iterations of the pressure-only run at most: a few variables, each a pressure.
constexpr int kBaselineIterations = 50;

[[noreturn]] void bad(const Design& d, const std::string& key, const std::string& message)
{
  throw InputError(design_problem(d, key, message));
}

std::vector<std::string> target_names(const Design& d)
{
  std::vector<std::string> names;
  for (const Target& t : d.targets) names.push_back(t.name);
  return names;
}

/// Puts the clearance barrier between fibers on when the start (optimization_start) is clear, so that
/// no path of the optimizer crosses two fibers (whether they crossed hinged on rounding, and crossed
/// fibers can lock together at their fixed ends). Returns whether it is on.
bool keep_fibers_apart(StageContext& ctx, RoutingProblem& problem, const SurfaceDistance& skin, const Routing& start,
                       std::unique_ptr<FiberClearance>& measure, std::unique_ptr<ClearanceBarrier>& barrier)
{
  const Design& d = ctx.design;
  if (start.routes.size() < 2) return false;
  measure = std::make_unique<FiberClearance>(design_clearance(d, skin, start.routes, start.routes));
  if (!measure->contacts(measure->lines(start.routes), d.collide.clearance, false).empty()) return false;
  barrier = std::make_unique<ClearanceBarrier>(*measure, start.routes, d.collide.clearance, d.muscle.model.radius());
  problem.set_clearance_barrier(barrier.get(), kClearanceBarrierWeight);
  ctx.log.info("the fibers start clear of each other; a barrier keeps them {:.2f} mm apart",
               d.collide.clearance / units::mm);
  return true;
}

/// ", turn off by 3.2° RMS, 7.1° at most" where the target's orientation is tracked, else "".
std::string turn_error(const TargetErrors& e)
{
  if (!e.orientation_tracked) return "";
  return fmt::format(", turn off by {:.1f}° RMS, {:.1f}° at most", e.orientation_rms / units::degree,
                     e.orientation_max / units::degree);
}

/// The progress and log line of an iteration: which start and fiber stage it is in, and its figures.
std::string iteration_line(int starts, int start, int stages, int stage, const MinimizerIteration& it,
                           const RoutingTerms& terms)
{
  return fmt::format("{}{}iteration {}: objective {:.4g} (distance {:.4g}), |∇| {:.2g}",
                     starts > 1 ? fmt::format("start {}/{}, ", start + 1, starts) : "",
                     stage < 0    ? "routes only, "
                     : stages > 1 ? fmt::format("fiber {}/{}, ", stage + 1, stages)
                                  : "",
                     it.iteration, terms.total, terms.distance, it.gradient_norm);
}

/// The optimization from the first guess and, with [optimize] starts = N, from N − 1 perturbations
/// of it (moved by up to one muscle diameter): the run that ends lowest, and each run's figures for
/// report.json in `runs`. `current` tells the callback which run it is in.
RoutingResult optimize_from_starts(StageContext& ctx, RoutingProblem& problem, const Routing& start,
                                   const MinimizerOptions& o, const RoutingCallback& on_iteration, int& current,
                                   nlohmann::ordered_json& runs)
{
  const Design& d = ctx.design;
  const SeveralStartsOptions options{d.optimize.strategy, o,
                                     actuator_mask(d),    d.optimize.route_only_iterations,
                                     d.optimize.starts,   d.muscle.model.diameter};
  std::vector<StartRun> ran;
  RoutingResult best = optimize_from_starts(problem, start, options, on_iteration, ctx.progress, current, ran);
  runs = nlohmann::ordered_json::array();
  for (const StartRun& run : ran) {
    const RoutingResult& r = run.result;
    if (!run.left_out.empty()) {
      ctx.log.warn("start {} of {} left out: {}", run.start + 1, d.optimize.starts, run.left_out);
      runs.push_back({{"start", run.start}, {"left_out", run.left_out}});
      continue;
    }
    runs.push_back({{"start", run.start},
                    {"objective", r.value},
                    {"termination", choice_name(r.termination)},
                    {"converged", r.converged},
                    {"iterations", r.iterations}});
    if (d.optimize.starts > 1)
      ctx.log.info("start {} of {}{}: objective {:.6g}, {} after {} iterations", run.start + 1, d.optimize.starts,
                   run.start == 0 ? " (the first guess)" : "", r.value, choice_name(r.termination), r.iterations);
  }
  return best;
}

/// The first guess's routes at their best pressures (a pressure-only run): the baseline every
/// optimization reports beside its own result and must beat or equal.
struct Baseline {
  RoutingResult result;
  nlohmann::ordered_json
      json; ///< {objective, iterations, termination, targets: {name: {rmse_mm, max_error_mm, pressure_kPa}}}
  std::vector<std::string> warnings; ///< first_guess_warnings (targets its muscles work against), and why it is kept
};
Baseline first_guess_at_best_pressures(StageContext& ctx, DesignRouting& dr, const MinimizerOptions& o,
                                       const Routing& start)
{
  RoutingProblem& problem = *dr.problem;
  MinimizerOptions pressures_only = o;
  pressures_only.max_iterations = std::min(o.max_iterations, kBaselineIterations);
  const RoutingCallback log = [&](int, const MinimizerIteration& it, const RoutingTerms& terms) {
    ctx.log.info("first guess, pressures only, iteration {}: objective {:.4g} (distance {:.4g})", it.iteration,
                 terms.total, terms.distance);
  };
  Baseline b{optimize_pressures(problem, pressures_only, log, ctx.progress, actuator_mask(ctx.design)), {}, {}};
  problem.set_base(start);
  if (b.result.interrupted) return b;
  nlohmann::ordered_json targets = nlohmann::ordered_json::object();
  std::vector<double> rmse;
  for (int t = 0; t < problem.num_targets(); ++t) {
    const TargetErrors e = target_errors(problem, dr.mesh, t, problem.equilibrium(b.result.routing, t));
    rmse.push_back(e.rmse);
    nlohmann::ordered_json pressures = nlohmann::ordered_json::object();
    for (int f = 0; f < problem.num_fibers(); ++f)
      pressures[b.result.routing.routes[f].name] = b.result.routing.pressures(t, f) / units::kPa;
    targets[dr.target_names[t]] = errors_json(e);
    targets[dr.target_names[t]]["pressure_kPa"] = pressures;
    ctx.log.info("target {}: the first guess at its best pressures: RMSE {:.3f} mm, max {:.3f} mm{}",
                 dr.target_names[t], e.rmse / units::mm, e.max / units::mm, turn_error(e));
  }
  b.warnings = first_guess_warnings(b.result.routing.pressures, actuator_mask(ctx.design), routing_settings(ctx.design),
                                    rmse, dr.target_names);
  for (const std::string& w : b.warnings) ctx.log.warn("{}", w);
  // The optimization's solves start from the start's equilibria again, as without this run.
  for (int t = 0; t < problem.num_targets(); ++t) problem.equilibrium(start, t);
  b.json = {{"objective", b.result.value},
            {"iterations", b.result.iterations},
            {"termination", choice_name(b.result.termination)},
            {"targets", targets}};
  return b;
}

/// Never worse than the first guess at its best pressures, in objective or in the targets' match
/// (compare_with_first_guess): where the optimizer ended worse, the first guess becomes the
/// result, and the warning that says so joins the baseline's. Whether it is kept. Sets the first
/// guess's objective and distance in its report to the full ones.
bool keep_the_better(StageContext& ctx, RoutingProblem& problem, Baseline& baseline, RoutingResult& result)
{
  if (result.interrupted) return false;
  // Both scored as the optimization's last run scores (free_as_optimized: a left-out perturbed start
  // can leave another mask set): the optimized routing first, its solve warm-started from the
  // optimization's last (the same equilibrium branch); then the first guess with its routes' terms
  // (curvature, skin, bend), which the pressure-only run leaves out as constants, at exactly its
  // routing (the variables the optimization left unfree taken from it too). Where the optimized
  // routing scores other than the result (another equilibrium found), its objective is compared
  // alone.
  const Routing base = problem.base();
  free_as_optimized(problem, ctx.design.optimize.strategy, actuator_mask(ctx.design));
  RoutingTerms first_guess, optimized;
  first_guess.total = optimized.total = HUGE_VAL;
  try {
    problem.evaluate(problem.variables(result.routing), nullptr, &optimized);
    problem.set_base(baseline.result.routing);
    problem.evaluate(problem.variables(baseline.result.routing), nullptr, &first_guess);
  } catch (const Interrupted&) {
    result.interrupted = true; // the caller keeps the best design so far
  }
  problem.set_base(base);
  if (!std::isfinite(first_guess.total)) return false;
  baseline.json["objective"] = first_guess.total;
  baseline.json["distance"] = first_guess.distance;
  constexpr double kSameScore = 1e-6; // relative: a re-solve from a nearby state, to Newton's tolerance
  if (!(std::abs(optimized.total - result.value) <= kSameScore * std::abs(result.value))) {
    optimized = RoutingTerms{};
    optimized.total = result.value; // its distance unknown: 0 claims no worse match
  }
  const FirstGuessComparison verdict = compare_with_first_guess(first_guess, optimized);
  if (!verdict.keep_first_guess) return false;
  ctx.log.warn("{}", verdict.warning);
  result.routing = baseline.result.routing;
  result.value = first_guess.total;
  baseline.warnings.push_back(verdict.warning);
  return true;
}

/// The Newton solves' counts and times.
nlohmann::ordered_json newton_json(RoutingProblem& problem)
{
  const NewtonTotals& n = problem.newton();
  return {{"solves", n.solves},
          {"assemblies", n.assemblies},
          {"factorizations", n.factorizations},
          {"hessian_products", n.products},
          {"symbolic_analyses", problem.simulation().symbolic_analyses()},
          {"seconds_assembly", n.seconds_assembly},
          {"seconds_factorization", n.seconds_factorization}};
}

/// Target t's entry in report.json, with its deformed state written: the errors at equilibrium x
/// of the optimized routing `r` against those at the start, the pressures, and the errors of a
/// solve from rest.
nlohmann::ordered_json target_report(StageContext& ctx, DesignRouting& dr, const Routing& r, int t,
                                     const Eigen::VectorXd& x, const TargetErrors& before, const TargetErrors& after,
                                     const TargetReach& reach, const std::vector<ReachedPose>& reached)
{
  const Design& d = ctx.design;
  RoutingProblem& problem = *dr.problem;
  const std::string& name = dr.target_names[t];
  // A robot starts from rest: where that leads elsewhere, the body has more than one equilibrium.
  // Its time is the paper's "sim (s)" of Table II.
  const auto rest_started = Clock::now();
  const int rest_newton = problem.newton().iterations;
  const Eigen::VectorXd at_rest = problem.equilibrium(r, t);
  const double rest_seconds = since(rest_started);
  const TargetErrors from_rest = target_errors(problem, dr.mesh, t, at_rest);
  if (std::abs(from_rest.rmse - after.rmse) > 0.1 * after.rmse + 0.01 * units::mm)
    ctx.log.warn("target {}: solved from rest, the body reaches another equilibrium than the optimizer's: RMSE {:.3f} "
                 "mm instead of {:.3f} mm",
                 name, from_rest.rmse / units::mm, after.rmse / units::mm);
  write_deformed_target(ctx.output_dir / fmt::format("deformed-{}.vtu", name), dr, r, t, x);
  nlohmann::ordered_json pressures = nlohmann::ordered_json::object();
  for (int f = 0; f < problem.num_fibers(); ++f) pressures[d.fibers[f].name] = r.pressures(t, f) / units::kPa;
  nlohmann::ordered_json entry = errors_json(after);
  entry["pressure_kPa"] = pressures;
  entry["start"] = errors_json(before);
  entry["reached_percent"] = 100 * reach.reached;
  entry["from_rest"] = errors_json(from_rest);
  entry["from_rest"]["seconds"] = rest_seconds;
  entry["from_rest"]["newton_iterations"] = problem.newton().iterations - rest_newton;
  nlohmann::ordered_json poses = nlohmann::ordered_json::array();
  for (const ReachedPose& p : reached) poses.push_back(pose_report(p));
  entry["poses"] = std::move(poses);
  ctx.log.info("target {}: RMSE {:.3f} mm (from {:.3f}), max {:.3f} mm (from {:.3f}) on the tracking curves{}; surface "
               "RMSE {:.3f} mm, max {:.3f} mm",
               name, after.rmse / units::mm, before.rmse / units::mm, after.max / units::mm, before.max / units::mm,
               turn_error(after), after.surface_rmse / units::mm, after.surface_max / units::mm);
  return entry;
}

/// Each target's report entry (and deformed state) for the optimized routing, and how the
/// optimization ended, its warnings logged.
OptimizationEnding report_targets(StageContext& ctx, DesignRouting& dr, const RoutingResult& result,
                                  const std::vector<TargetErrors>& before, nlohmann::ordered_json& per_target)
{
  const Design& d = ctx.design;
  RoutingProblem& problem = *dr.problem;
  const int targets = problem.num_targets();
  std::vector<Eigen::VectorXd> optimized; // the equilibria the optimizer scored (warm-started)
  std::vector<TargetErrors> after;
  // Where the optimized robot's regions and tracking curves' ends went; for a pose target, the angle reached of the
  // angle asked.
  std::vector<std::vector<PosedRegion>> asked(static_cast<std::size_t>(targets));
  std::vector<std::vector<ReachedPose>> reached(static_cast<std::size_t>(targets));
  std::vector<std::vector<AngleReach>> angles(static_cast<std::size_t>(targets));
  for (int t = 0; t < targets; ++t) {
    optimized.push_back(problem.equilibrium(result.routing, t));
    after.push_back(target_errors(problem, dr.mesh, t, optimized[t]));
    const Target& target = d.targets[static_cast<std::size_t>(t)];
    if (target.kind == TargetKind::pose) asked[t] = target_poses(d, target, dr.mesh);
    reached[t] = reached_poses(d, target, problem.simulation(), optimized[t], asked[t]);
    for (const ReachedPose& p : reached[t])
      if (p.asked) {
        angles[t].push_back({p.place, p.asked->angle, p.motion.angle_about(p.asked->axis)});
        ctx.log.info("target {}: {} turned {:.2f}° of the {:.2f}° asked about ({:.3f}, {:.3f}, {:.3f})",
                     dr.target_names[t], p.place, angles[t].back().reached / units::degree,
                     p.asked->angle / units::degree, p.asked->axis.x(), p.asked->axis.y(), p.asked->axis.z());
      }
  }
  problem.forget_states();
  std::vector<std::string> fiber_names;
  for (const Fiber& f : d.fibers) fiber_names.push_back(f.name);
  OptimizationEnding ending = optimization_ending(result, actuator_mask(d), routing_settings(d), before, after, angles,
                                                  dr.target_names, fiber_names);
  for (int t = 0; t < targets; ++t) {
    ctx.progress.checkpoint(1, "writing target " + dr.target_names[t]);
    per_target[dr.target_names[t]] =
        target_report(ctx, dr, result.routing, t, optimized[t], before[t], after[t], ending.targets[t], reached[t]);
  }
  for (const std::string& w : ending.warnings) ctx.log.warn("{}", w);
  return ending;
}

/// With [optimize] refine: the refined solve's mesh refused before the optimization, not after it,
/// by the rule check uses; the body's surface, prepared for it, and its volume kept for the solve.
void require_refinable(const Design& d, SurfaceMesh& surface, double& volume)
{
  if (!d.optimize.refine) return;
  SurfaceCheck check;
  RepairReport repair;
  nlohmann::json seconds;
  surface = prepared_surface(d, check, repair, seconds);
  volume = check.volume;
  require_refined_mesh_size(d, surface, volume);
}

/// With [optimize] refine: each target's optimized actuation solved from rest on a mesh of half
/// the edge length, against the same on the design's mesh (docs/optimize.md, "Discretization
/// error"), into the target's report entry; a warning (logged and added to `warnings`) where the
/// difference exceeds the error to the target, which the mesh then cannot resolve.
/// `surface` and `volume`: the body's, from require_refinable.
void report_refinement(StageContext& ctx, DesignRouting& dr, const SurfaceMesh& surface, double volume,
                       const Routing& r, nlohmann::ordered_json& per_target, std::vector<std::string>& warnings)
{
  const Design& d = ctx.design;
  RoutingProblem& problem = *dr.problem;
  ctx.progress.checkpoint(-1, "meshing at half the edge length");
  const TetMesh fine_mesh = refined_design_mesh(d, surface, volume, ctx.progress);
  const MuscleModel model(d.muscle.model);
  for (int t = 0; t < problem.num_targets(); ++t) {
    const std::string& name = dr.target_names[t];
    ctx.progress.checkpoint(-1, fmt::format("target {} on {} tets", name, fine_mesh.num_tets()));
    const auto started = Clock::now();
    problem.forget_states();
    const Eigen::VectorXd coarse = problem.equilibrium(r, t);
    Simulation fine(fine_mesh, simulation_options(d, fine_mesh));
    std::vector<Actuation> actuations;
    for (std::size_t f = 0; f < r.routes.size(); ++f)
      actuations.push_back(
          {r.routes[f].name, r.routes[f].points, r.routes[f].tangents, r.pressures(t, static_cast<Eigen::Index>(f))});
    add_muscles(fine, d, model, actuations);
    Eigen::VectorXd x = fine.rest();
    const NewtonSummary summary = fine.solve(x, ctx.progress);
    if (!summary.converged) {
      warnings.push_back(
          fmt::format("target {}: the refined solve ({} tets) did not reach equilibrium ({}); no discretization figure",
                      name, fine_mesh.num_tets(), summary.brief()));
      ctx.log.warn("{}", warnings.back());
      continue;
    }
    const Refinement f = compare_refined(d, problem.simulation(), coarse, fine, x);
    const double seconds = since(started);
    auto& entry = per_target[name];
    entry["refined"] = {{"edge_length_mm", f.edge_length / units::mm},
                        {"nodes", f.nodes},
                        {"tets", f.tets},
                        {"curves_max_mm", f.curves_max / units::mm},
                        {"curves_rms_mm", f.curves_rms / units::mm},
                        {"surface_max_mm", f.surface_max / units::mm},
                        {"surface_rms_mm", f.surface_rms / units::mm},
                        {"seconds", seconds}};
    ctx.log.info(
        "target {}: on half the edge length ({} tets) the optimized robot's tracking curves move {:.3f} mm RMS, "
        "{:.3f} mm at most; its surface {:.3f} mm RMS, {:.3f} mm at most ({:.1f} s)",
        name, f.tets, f.curves_rms / units::mm, f.curves_max / units::mm, f.surface_rms / units::mm,
        f.surface_max / units::mm, seconds);
    const double error = entry.value("rmse_mm", 0.0) * units::mm;
    if (f.curves_rms > error) {
      warnings.push_back(fmt::format(
          "target {}: on a mesh of half the edge length the optimized robot's tracking curves move {:.2f} mm RMS, more "
          "than its "
          "error to the target ({:.2f} mm): that error is not resolved by the mesh; lower [mesh] edge_length",
          name, f.curves_rms / units::mm, error / units::mm));
      ctx.log.warn("{}", warnings.back());
    }
  }
}

/// What is wrong with a starting route `closest` from the skin at `where`, and how to mend it.
std::string too_near_the_skin(const Design& d, double closest, const Eigen::Vector3d& where)
{
  const SkinDistance need = skin_distance(d);
  return fmt::format(
      "the starting route passes {:.3f} mm from the skin at {}, where the optimizer keeps a fiber's centre line "
      "more than {:.3f} mm inside ({}): move the route more than {:.3f} mm inward there, or give a thinner "
      "muscle or {}",
      closest / units::mm, format_mm(where), need.distance / units::mm, need.terms,
      std::max(0.0, need.distance - closest) / units::mm,
      need.groove_margin > 0 ? "a smaller [mold] groove_clearance or min_silicone" : "a smaller clearance");
}

/// A starting route that leaves the body along the skin rather than into it: where, and what to do.
std::string leaves_along_the_skin(const Design& d, const ExitShortfall& e)
{
  const SkinDistance need = skin_distance(d);
  const double stretch = 2 * (need.distance + routing_settings(d).skin_band);
  return fmt::format(
      "the starting route leaves the body along the skin, not into it: at {}, {:.1f} mm from its end on "
      "the skin, it is {:.3f} mm from the skin, where a route is kept more than {:.3f} mm inside (rising to {:.3f} mm "
      "at {:.1f} mm from the end: a route leaving a flat face within {:.0f}° of its normal clears it): point the end's "
      "tangent into the body, or move the point next to the end inward",
      format_mm(e.where), e.from_end / units::mm, e.distance / units::mm, e.required / units::mm,
      need.distance / units::mm, stretch / units::mm,
      std::acos(std::min(1.0, need.distance / stretch)) / units::degree);
}

/// A starting route, as moved apart from the other fibers, that the skin barrier or the bend radius
/// refuses (InputError at the fiber): require_optimizable checked the [[fiber]] routes.
void require_start_inside(const Design& d, RoutingProblem& problem, const Routing& start)
{
  double closest = 0;
  Eigen::Vector3d where;
  if (const int f = problem.skin_violation(start, closest, where); f >= 0)
    bad(d, fmt::format("[fiber.{}]", d.fibers[f].name), too_near_the_skin(d, closest, where));
  ExitShortfall exit;
  if (const int f = problem.exit_violation(start, exit); f >= 0)
    bad(d, fmt::format("[fiber.{}]", d.fibers[f].name), leaves_along_the_skin(d, exit));
  // The start may differ from the [[fiber]] routes: fibers closer than the clearance are moved apart.
  require_bend_radius(d, start.routes, "the starting route, as moved apart from the other fibers,", false);
}

/// An interrupted run's best design and history, kept beside the outputs (which stay as they were).
[[noreturn]] void keep_interrupted(StageContext& ctx, const FibersFile& fibers, const RoutingHistory& history,
                                   int iterations, double objective)
{
  const fs::path kept = ctx.build_dir / "optimize.interrupted";
  fs::create_directories(kept);
  write_file_atomic(kept / "fibers.json", fibers_json(fibers));
  write_file_atomic(kept / "history.csv", history.text());
  ctx.log.warn("interrupted after {} iterations; the best design so far (objective {:.4g}) is in {}", iterations,
               objective, kept.string());
  throw Interrupted();
}

} // namespace

void require_optimizable(const Design& d, const SurfaceDistance& skin)
{
  if (!d.optimize.enabled) return;
  if (d.fibers.empty()) bad(d, "[[fiber]]", "nothing to optimize: give at least one fiber");
  if (d.targets.empty()) bad(d, "[[target]]", "nothing to optimize for: give at least one target");
  if (d.tracking_curves.empty())
    bad(d, "[[tracking_curve]]", "the optimizer compares deformations along tracking curves: give at least one");
  if (d.optimize.strategy == Strategy::sequential && d.fibers.size() != d.targets.size())
    bad(d, "[optimize].strategy",
        fmt::format("sequential drives one fiber per target, in order: {} fiber(s) for {} target(s)", d.fibers.size(),
                    d.targets.size()));
  const SkinDistance need = skin_distance(d);
  for (const Fiber& f : d.fibers) {
    const HermiteSpline s(f.points, f.tangents);
    for (const Eigen::Vector3d& c : split_into_segments(s, segment_count(s, d.muscle.segments_per_length)).centres)
      if (!skin.closest(c).inside) {
        const auto inside = [&](const Eigen::Vector3d& q) { return skin.holds(q, 1e-6); };
        bad(d, points_key(fmt::format("[fiber.{}]", f.name), f.points, inside),
            leaves_the_body(
                "fiber", f.points, c, inside, [&](const Eigen::Vector3d& q) { return skin.closest(q).distance; },
                &need));
      }
  }
  const Routing start = starting_routing(d);
  const RoutingSettings settings = routing_settings(d);
  for (std::size_t f = 0; f < start.routes.size(); ++f) {
    const SkinBarrier barrier = route_skin_barrier(skin, settings, start.routes[f]);
    const HermiteSpline route(start.routes[f].points, start.routes[f].tangents);
    Eigen::Vector3d where;
    if (const double closest = barrier.closest_approach(route, where); closest <= settings.skin_distance)
      bad(d, fmt::format("[fiber.{}].points", d.fibers[f].name), too_near_the_skin(d, closest, where));
    if (const auto e = barrier.exit_shortfall(route))
      bad(d, fmt::format("[fiber.{}].points", d.fibers[f].name), leaves_along_the_skin(d, *e));
  }
  tracking_samples(d, skin);
}

void OptimizeStage::run(StageContext& ctx) const
{
  const Design& d = ctx.design;
  const auto started = Clock::now();
  const std::vector<std::string> names = target_names(d);
  require_bend_radius(d, starting_routing(d).routes, "the starting route", true);
  if (!d.optimize.enabled) {
    write_file_atomic(ctx.output_dir / "fibers.json", fibers_json({starting_routing(d), names, false}));
    write_json_atomic(ctx.output_dir / "report.json", nlohmann::ordered_json{{"optimized", false}});
    ctx.log.info("[optimize] enabled = false: the [[fiber]] routes pass through unchanged");
    return;
  }
  DesignRouting dr(ctx);
  require_optimizable(d, *dr.skin);
  SurfaceMesh surface; // with [optimize] refine, the body's, prepared once
  double volume = 0;
  require_refinable(d, surface, volume);
  const OptimizationStart begun = optimization_start(d, *dr.skin);
  for (const std::string& line : begun.log) ctx.log.info("{}", line);
  if (!begun.warning.empty()) ctx.log.warn("{}", begun.warning);
  const Routing& start = begun.routing;
  RoutingProblem& problem = dr.start(start);
  if (begun.moved) require_start_inside(d, problem, start);

  std::unique_ptr<FiberClearance> measure;
  std::unique_ptr<ClearanceBarrier> barrier;
  const bool kept_apart = keep_fibers_apart(ctx, problem, *dr.skin, start, measure, barrier);

  std::vector<TargetErrors> before;
  for (int t = 0; t < problem.num_targets(); ++t)
    before.push_back(target_errors(problem, dr.mesh, t, problem.equilibrium(start, t)));
  for (int t = 0; t < problem.num_targets(); ++t)
    ctx.log.info("target {}: at the start, RMSE {:.3f} mm, max {:.3f} mm on the tracking curves{}", names[t],
                 before[t].rmse / units::mm, before[t].max / units::mm, turn_error(before[t]));

  const MinimizerOptions o = minimizer_options(d);
  Baseline baseline = first_guess_at_best_pressures(ctx, dr, o, start);
  RoutingHistory history(names);
  int iterations = 0;
  const int stages = d.optimize.strategy == Strategy::sequential ? static_cast<int>(d.fibers.size()) : 1;
  // Progress over the iteration budget: the route-only ones, then max_iterations per stage.
  const double per_start = d.optimize.route_only_iterations + stages * std::max(1, o.max_iterations);
  const double budget = d.optimize.starts * per_start;
  int current_start = 0;
  int route_only_done = 0;
  const RoutingCallback on_iteration = [&](int stage, const MinimizerIteration& it, const RoutingTerms& terms) {
    ++iterations;
    history.add(iterations, stage, it, terms, since(started), current_start);
    if (stage < 0) route_only_done = it.iteration; // of this start's route-only run
    const std::string what = iteration_line(d.optimize.starts, current_start, stages, stage, it, terms);
    const double done =
        current_start * per_start +
        (stage < 0 ? route_only_done : route_only_done + stage * std::max(1, o.max_iterations) + it.iteration);
    ctx.progress.update(done / budget, what);
    ctx.log.info("{}", what);
  };
  nlohmann::ordered_json runs = nlohmann::ordered_json::array();
  RoutingResult result = baseline.result.interrupted
                             ? baseline.result
                             : optimize_from_starts(ctx, problem, start, o, on_iteration, current_start, runs);
  const bool kept_first_guess = keep_the_better(ctx, problem, baseline, result);
  const FibersFile fibers{result.routing, names, true};

  if (result.interrupted) keep_interrupted(ctx, fibers, history, baseline.result.iterations + iterations, result.value);
  ctx.log.info("{}: {} after {} iterations, {} evaluations", choice_name(result.termination), result.message,
               result.iterations, result.evaluations);

  nlohmann::ordered_json per_target = nlohmann::ordered_json::object();
  OptimizationEnding ending = report_targets(ctx, dr, result, before, per_target);
  ending.warnings.insert(ending.warnings.end(), baseline.warnings.begin(), baseline.warnings.end());
  if (d.optimize.refine) report_refinement(ctx, dr, surface, volume, result.routing, per_target, ending.warnings);
  const nlohmann::ordered_json report{
      {"optimized", true},
      {"strategy", choice_name(d.optimize.strategy)},
      {"method", choice_name(d.optimize.method)},
      {"termination", choice_name(result.termination)},
      {"converged", result.converged},
      {"message", result.message},
      {"warnings", ending.warnings},
      {"fibers_kept_apart", kept_apart},
      {"first_guess", baseline.json},
      {"kept", kept_first_guess ? "first guess" : "optimized"},
      {"starts", runs},
      {"min_bend_radius_mm", d.muscle.min_bend_radius / units::mm},
      {"bends", {{"start", bends_json(start.routes)}, {"end", bends_json(result.routing.routes)}}},
      {"iterations", result.iterations},
      {"evaluations", result.evaluations},
      {"refused", problem.refusals()},
      {"objective", result.value},
      {"newton_iterations", problem.newton().iterations},
      {"newton", newton_json(problem)},
      {"seconds",
       {{"total", since(started)},
        {"simulation", problem.seconds_simulation()},
        {"adjoint", problem.seconds_adjoint()},
        {"model", problem.seconds_model()}}},
      {"targets", per_target}};
  write_file_atomic(ctx.output_dir / "fibers.json", fibers_json(fibers));
  write_file_atomic(ctx.output_dir / "history.csv", history.text());
  write_json_atomic(ctx.output_dir / "report.json", report);
}

} // namespace fibermold
