#pragma once
// What the optimize and collide stages share: the design's routing problem (eq. 4), and how well a
// routing does against each target, on the tracking curves and on the surface.

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "design/design.hpp"
#include "make/stage.hpp"
#include "mesh/surface_distance.hpp"
#include "mesh/tet_mesh.hpp"
#include "optimize/fiber_clearance.hpp"
#include "optimize/routing_optimizer.hpp"
#include "optimize/target_errors.hpp"

namespace fibermold {

/// The samples of every tracking curve; InputError at the curve when one leaves the body (`skin`).
std::vector<TrackingSamples> tracking_samples(const Design& d, const SurfaceDistance& skin);

/// The body, its skin, the targets and the tracking curves of a design, and the routing problem
/// over them; built from the mesh and targets stages' outputs.
struct DesignRouting {
  const Design& design;
  TetMesh mesh;
  std::unique_ptr<SurfaceDistance> skin;
  std::unique_ptr<Simulation> sim;
  MuscleModel model;
  std::vector<std::string> target_names;
  std::vector<Eigen::VectorXd> targets;
  std::vector<TrackingSamples> curves;
  std::unique_ptr<RoutingProblem> problem; ///< after start()

  /// Throws InputError for a tracking curve that leaves the body.
  explicit DesignRouting(const StageContext& ctx);
  /// The routing problem from `routing`, which also fixes where the muscles' segments sit on the
  /// splines (the optimizer's: from the design's starting routing); std::invalid_argument when it
  /// refuses it.
  RoutingProblem& start(const Routing& routing);

  DesignRouting(const DesignRouting&) = delete; // the simulation holds the mesh
  DesignRouting& operator=(const DesignRouting&) = delete;
};

/// The [optimize] weights, [muscle] limits and the skin distance ([muscle] diameter/2 + [collide]
/// clearance) as the routing problem takes them.
RoutingSettings routing_settings(const Design& d);

/// Per fiber, the parameters where the optimizer's skin barrier holds a routing that started at
/// `start` off the skin (all but an end's stretch on the skin): collide tests the skin there.
std::vector<HeldStretch> skin_held(const Design& d, const SurfaceDistance& skin, const std::vector<Route>& start);
/// The clearance measure of `routes` with the design's muscle, clearance, sampling and groove
/// margin, testing the skin where the optimizer that started from `start` held it (skin_held).
FiberClearance design_clearance(const Design& d, const SurfaceDistance& skin, const std::vector<Route>& routes,
                                const std::vector<Route>& start);

/// Weight of the clearance barrier between fibers (optimize/clearance_barrier.hpp), which is ∫ b ds
/// over the fibers in contact (mm): small, so that it does not outweigh the targets while it stays
/// infinite at the clearance (as IPC's κ).
inline constexpr double kClearanceBarrierWeight = 4e-3;
/// Fibers moved apart for a barrier are moved this much beyond the clearance: the barrier is
/// infinite at the clearance itself, and an optimizer needs room inside it (m).
inline constexpr double kBarrierRoom = 0.1e-3;

/// Which fibers drive which target: a target's `actuators`, all fibers when it names none, fiber k
/// alone for target k with the sequential strategy.
ActuatorMask actuator_mask(const Design& d);

/// The [[fiber]] routes; pressures half the maximum for each target's actuators, 0 for the others.
Routing starting_routing(const Design& d);

/// The routing the optimizer starts from (docs/optimize.md, "clearance barrier"): the [[fiber]]
/// routes, and where two start closer than the [collide] clearance, moved apart to it + kBarrierRoom
/// by collide's resolution (optimize/collision_resolution.hpp), so that the barrier between fibers
/// holds from the first iteration. Collide takes its muscle segments from it, as the optimizer had
/// them. `log`: what was done, one line each; `warning`: why a start could not be moved apart (two
/// fixed ends too close), else empty.
struct OptimizationStart {
  Routing routing;
  std::vector<std::string> log;
  std::string warning;
  bool moved = false; ///< the routes were moved apart: not the [[fiber]] routes that require_optimizable checked
};
OptimizationStart optimization_start(const Design& d, const SurfaceDistance& skin);

/// InputError at the first route that bends tighter than [muscle] min_bend_radius anywhere along
/// it (bend_radius.hpp): where, by how much, and what to do. `whose`: "the starting route", ….
/// `as_drawn`: the routes are the [[fiber]] routes as the design file gives them, and the error
/// is placed at their points; else at the fiber.
void require_bend_radius(const Design& d, const std::vector<Route>& routes, std::string_view whose, bool as_drawn);
/// Each route's smallest bend radius and where, for the reports: {fiber: {min_bend_radius_mm,
/// at_mm, along_mm}}; a straight route's is {straight: true} (its radius infinite).
nlohmann::ordered_json bends_json(const std::vector<Route>& routes);

/// The [optimize] stopping rules.
MinimizerOptions minimizer_options(const Design& d);

/// {rmse_mm, max_error_mm, surface_rmse_mm, surface_max_error_mm}, and {orientation_rms_deg,
/// orientation_max_deg} where a tracking curve's orientation is tracked.
nlohmann::ordered_json errors_json(const TargetErrors& e);

/// Target t's deformed state for the report: every node's position and each fiber's centre line (mm).
std::string deformed_json(DesignRouting& dr, const Routing& r, int t, const Eigen::VectorXd& x);

/// deformed-<target>.vtu of equilibrium x of target t under routing r.
void write_deformed_target(const std::filesystem::path& path, DesignRouting& dr, const Routing& r, int t,
                           const Eigen::VectorXd& x);

} // namespace fibermold
