#include "stages/routing_evaluation.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/array_file.hpp"
#include "core/input_error.hpp"
#include "core/json_file.hpp"
#include "core/units.hpp"
#include "optimize/collision_resolution.hpp"
#include "stages/design_simulation.hpp"
#include "stages/skin_distance.hpp"

namespace fibermold {

std::vector<TrackingSamples> tracking_samples(const Design& d, const SurfaceDistance& skin)
{
  std::vector<TrackingSamples> curves;
  for (const TrackingCurve& c : d.tracking_curves) {
    curves.push_back(sample_tracking_curve(c.points, c.samples, c.weight_position, c.weight_orientation));
    const auto in_body = [&](const Eigen::Vector3d& p) { return skin.holds(p, 1e-6); };
    for (const Eigen::Vector3d& q : curves.back().points)
      if (!in_body(q))
        throw InputError(design_problem(d, points_key(fmt::format("[tracking_curve.{}]", c.name), c.points, in_body),
                                        leaves_the_body("curve", c.points, q, in_body)));
  }
  return curves;
}

DesignRouting::DesignRouting(const StageContext& ctx)
    : design(ctx.design), mesh(load_tet_mesh(ctx.upstream("mesh", "body.tetmesh"))), model(ctx.design.muscle.model)
{
  const Design& d = ctx.design;
  skin = std::make_unique<SurfaceDistance>(mesh.nodes, mesh.boundary_faces);
  curves = tracking_samples(d, *skin);
  sim = std::make_unique<Simulation>(mesh, simulation_options(d, mesh));
  for (const Target& t : d.targets) {
    target_names.push_back(t.name);
    targets.push_back(load_array(ctx.upstream("targets", t.name + ".positions"), "positions"));
  }
}

RoutingProblem& DesignRouting::start(const Routing& routing)
{
  problem = std::make_unique<RoutingProblem>(*sim, model, *skin, targets, curves, routing, routing_settings(design));
  return *problem;
}

void require_bend_radius(const Design& d, const std::vector<Route>& routes, std::string_view whose, bool as_drawn)
{
  const double limit = d.muscle.min_bend_radius;
  if (!(limit > 0)) return;
  for (const Route& r : routes) {
    const SmallestBend b = smallest_bend(HermiteSpline(r.points, r.tangents));
    if (b.radius > limit) continue;
    throw InputError(
        design_problem(d, fmt::format("[fiber.{}]{}", r.name, as_drawn ? ".points" : ""),
                       fmt::format("{} bends with a radius of {:.2f} mm at {}, {:.1f} mm along it, tighter than "
                                   "[muscle] min_bend_radius = {:g} mm "
                                   "(short by {:.2f} mm): spread its control points or straighten its tangents there, "
                                   "or lower min_bend_radius "
                                   "if the muscle takes a tighter bend",
                                   whose, b.radius / units::mm, format_mm(b.where), b.arc_length / units::mm,
                                   limit / units::mm, (limit - b.radius) / units::mm)));
  }
}

nlohmann::ordered_json bends_json(const std::vector<Route>& routes)
{
  nlohmann::ordered_json out = nlohmann::ordered_json::object();
  for (const Route& r : routes) {
    const SmallestBend b = smallest_bend(HermiteSpline(r.points, r.tangents));
    nlohmann::ordered_json e = nlohmann::ordered_json::object();
    if (std::isfinite(b.radius)) {
      e["min_bend_radius_mm"] = b.radius / units::mm;
      e["at_mm"] = {b.where.x() / units::mm, b.where.y() / units::mm, b.where.z() / units::mm};
      e["along_mm"] = b.arc_length / units::mm;
    } else {
      e["straight"] = true; // no bend: no radius, place or arc to give
    }
    out[r.name] = e;
  }
  return out;
}

RoutingSettings routing_settings(const Design& d)
{
  RoutingSettings s;
  s.max_pressure = d.muscle.max_pressure;
  s.segments_per_length = d.muscle.segments_per_length;
  s.skin_distance = skin_distance(d).distance;
  s.skin_band = d.muscle.model.radius();
  s.weight_curvature = d.optimize.weight_curvature;
  s.min_bend_radius = d.muscle.min_bend_radius;
  s.weight_skin = d.optimize.weight_skin_barrier;
  s.weight_bend = d.optimize.weight_bend_barrier;
  s.weight_pressure = d.optimize.weight_pressure_barrier;
  for (const Target& t : d.targets) s.target_weights.push_back(t.weight);
  return s;
}

ActuatorMask actuator_mask(const Design& d)
{
  const auto T = static_cast<Eigen::Index>(d.targets.size()), F = static_cast<Eigen::Index>(d.fibers.size());
  ActuatorMask m = ActuatorMask::Constant(T, F, d.optimize.strategy != Strategy::sequential);
  for (Eigen::Index t = 0; t < T; ++t) {
    if (d.optimize.strategy == Strategy::sequential && t < F) m(t, t) = true;
    const std::vector<std::string>& names = d.targets[t].actuators;
    if (names.empty()) continue;
    for (Eigen::Index f = 0; f < F; ++f)
      m(t, f) = std::find(names.begin(), names.end(), d.fibers[f].name) != names.end();
  }
  return m;
}

Routing starting_routing(const Design& d)
{
  Routing r;
  for (const Fiber& f : d.fibers) {
    const HermiteSpline s(f.points, f.tangents);
    r.routes.push_back({f.name, s.points(), s.tangents()});
  }
  r.pressures = actuator_mask(d).cast<double>() * (d.muscle.max_pressure / 2);
  return r;
}

std::vector<HeldStretch> skin_held(const Design& d, const SurfaceDistance& skin, const std::vector<Route>& start)
{
  const RoutingSettings settings = routing_settings(d);
  std::vector<HeldStretch> out;
  for (const Route& r : start) out.push_back(route_skin_barrier(skin, settings, r).held());
  return out;
}

FiberClearance design_clearance(const Design& d, const SurfaceDistance& skin, const std::vector<Route>& routes,
                                const std::vector<Route>& start)
{
  return FiberClearance(skin, routes, d.muscle.model.radius(), d.collide.clearance, d.collide.samples_per_length,
                        skin_distance(d).groove_margin, skin_held(d, skin, start));
}

OptimizationStart optimization_start(const Design& d, const SurfaceDistance& skin)
{
  OptimizationStart out{starting_routing(d), {}, {}, false};
  std::vector<Route>& routes = out.routing.routes;
  if (routes.size() < 2) return out;
  const FiberClearance measure = design_clearance(d, skin, routes, routes);
  if (measure.contacts(measure.lines(routes), d.collide.clearance + kBarrierRoom / 2, false).empty()) return out;
  ResolutionSettings settings;
  settings.clearance = d.collide.clearance;
  settings.room = kBarrierRoom;
  settings.smoothness = d.collide.smoothness;
  try {
    const CollisionResolution r = resolve_collisions(measure, routes, settings);
    for (const Contact& c : r.collided)
      if (!c.with_skin())
        out.log.push_back(fmt::format("fibers {} and {} start {:.2f} mm apart at {}, less than the [collide] clearance",
                                      routes[c.a].name, routes[c.b].name, c.clearance / units::mm,
                                      format_mm(c.point_a)));
    out.log.push_back(fmt::format(
        "moved apart before optimizing, in {} rounds: the smallest clearance went from {:.3f} mm to {:.3f} mm",
        r.iterations, r.before / units::mm, r.after / units::mm));
    routes = r.routes;
    out.moved = true;
  } catch (const CollisionError& e) {
    out.warning =
        fmt::format("the starting fibers cannot be moved apart ({}); the optimizer lets them cross, and collide parts "
                    "them afterwards",
                    e.what());
  }
  return out;
}

MinimizerOptions minimizer_options(const Design& d)
{
  MinimizerOptions o;
  o.max_iterations = d.optimize.max_iterations;
  o.gradient_tolerance = d.optimize.gradient_tolerance;
  o.relative_tolerance = d.optimize.relative_tolerance;
  o.method = d.optimize.method;
  o.decrease_tolerance = d.optimize.decrease_tolerance;
  return o;
}

nlohmann::ordered_json errors_json(const TargetErrors& e)
{
  nlohmann::ordered_json j = {{"rmse_mm", e.rmse / units::mm},
                              {"max_error_mm", e.max / units::mm},
                              {"surface_rmse_mm", e.surface_rmse / units::mm},
                              {"surface_max_error_mm", e.surface_max / units::mm}};
  if (e.orientation_tracked) {
    j["orientation_rms_deg"] = e.orientation_rms / units::degree;
    j["orientation_max_deg"] = e.orientation_max / units::degree;
  }
  return j;
}

void write_deformed_target(const std::filesystem::path& path, DesignRouting& dr, const Routing& r, int t,
                           const Eigen::VectorXd& x)
{
  const LameParameters lame =
      LameParameters::from_young_poisson(dr.design.material.youngs_modulus, dr.design.material.poisson_ratio);
  std::vector<const MuscleEnergy*> muscles;
  const auto owned = dr.problem->muscles(r, t);
  for (const auto& m : owned) muscles.push_back(m.get());
  write_deformed(path, *dr.sim, x, muscles, lame);
}

std::string deformed_json(DesignRouting& dr, const Routing& r, int t, const Eigen::VectorXd& x)
{
  const Eigen::MatrixX3d nodes = dr.sim->deformed_nodes(x);
  nlohmann::ordered_json points = nlohmann::ordered_json::array(), fibers = nlohmann::ordered_json::object();
  // To 0.1 µm: the report draws them in float32 anyway.
  const auto mm = [](const Eigen::Vector3d& p) {
    const auto r = [](double v) { return std::round(v / units::mm * 1e4) / 1e4; };
    return nlohmann::ordered_json{r(p.x()), r(p.y()), r(p.z())};
  };
  for (Eigen::Index i = 0; i < nodes.rows(); ++i) points.push_back(mm(nodes.row(i).transpose()));
  const auto muscles = dr.problem->muscles(r, t);
  for (std::size_t m = 0; m < muscles.size() && m < r.routes.size(); ++m) {
    nlohmann::ordered_json line = nlohmann::ordered_json::array();
    for (double s : muscles[m]->segments().t)
      line.push_back(mm(dr.sim->basis().at(muscles[m]->spline().position(s), 0).position(x)));
    fibers[r.routes[m].name] = line;
  }
  return checked_json(nlohmann::ordered_json{{"target", dr.target_names[static_cast<std::size_t>(t)]},
                                             {"nodes_mm", points},
                                             {"fibers_mm", fibers}},
                      fmt::format("deformed-{}.json", dr.target_names[static_cast<std::size_t>(t)]), -1);
}

} // namespace fibermold
