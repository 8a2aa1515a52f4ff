#pragma once
// How an optimization ended, in the terms a user acts on: why it stopped (and whether that is
// convergence), the muscles that ended at a limit of their pressure, and how much of each target
// was reached, with what to try when a target is far from reached. The optimize stage logs these
// and writes them into its report, whose warnings report.html shows as a banner.

#include <string>
#include <vector>

#include <Eigen/Core>

#include "optimize/routing_optimizer.hpp"
#include "optimize/target_errors.hpp"

namespace fibermold {

/// A target whose tracking-curve RMSE kept more than this share of its starting value is far from
/// reached.
inline constexpr double kFarFromReached = 1.0 / 3;
/// A pose's region that turned less than this share of its angle (but at least 1 − kFarFromReached)
/// is short of its turn: said with its muscles' pressures, as a lab would cast a robot that bends
/// 11° short of a 40° grasp with no word (a new user's starfish, at 273 and 282 of 425 kPa).
inline constexpr double kShortOfTurn = 0.9;

struct TargetReach {
  double start_rmse = 0, end_rmse = 0; ///< m, on the tracking curves
  double reached = 0;                  ///< 1 − end/start: the share of the way from the start to the target
};

/// A pose target's turn: the angle it asked of a region and the angle the optimized robot's region
/// turned about the asked axis (rad).
struct AngleReach {
  std::string place; ///< "pose[1]"
  double asked = 0, reached = 0;
};

/// A route whose tightest bend is within this share of [muscle] min_bend_radius is at that limit:
/// the bend radius, not the targets, decides it there. (The bend barrier acts from 1.11 R,
/// BendBarrier::kBand; a route it holds further out is not named.)
inline constexpr double kBendAtLimit = 0.02;

struct PressureLimit {
  int target = 0, fiber = 0;
  double pressure = 0; ///< Pa
  bool at_max = false; ///< at max_pressure; else at 0
};

struct BendLimit {
  int fiber = 0;
  double radius = 0; ///< m, the route's tightest bend
  Eigen::Vector3d where = Eigen::Vector3d::Zero();
};

struct OptimizationEnding {
  std::vector<TargetReach> targets;
  std::vector<PressureLimit> limits;
  std::vector<BendLimit> bends;      ///< routes at their smallest bend radius (kBendAtLimit)
  std::vector<std::string> warnings; ///< sentences naming the target, the fiber, the figures and what to try
};

/// `actuators` (targets × fibers): which fibers the optimizer could pressurize for which target;
/// the others are not reported at 0. A pressure within `settings.pressure_margin` of 0 or of
/// max_pressure is at that limit: there the pressure barrier, not the target, holds it.
/// A route bent within kBendAtLimit of settings.min_bend_radius is at that limit, named with where.
/// `angles[t]`: target t's turns (empty for a target that asks none); such a target is far from
/// reached when a region turned less than 2/3 of its angle, whatever the tracking curves say, and
/// short of its turn under kShortOfTurn of it.
OptimizationEnding optimization_ending(const RoutingResult& result, const ActuatorMask& actuators,
                                       const RoutingSettings& settings, const std::vector<TargetErrors>& before,
                                       const std::vector<TargetErrors>& after,
                                       const std::vector<std::vector<AngleReach>>& angles,
                                       const std::vector<std::string>& target_names,
                                       const std::vector<std::string>& fiber_names);

/// The first guess at its best pressures (`pressures`, targets × fibers; `rmse[t]` its tracking-curve
/// RMSE, m): a warning for each target whose every muscle does best there at 0 kPa (within the
/// pressure barrier's margin), where the routes as drawn work against the target.
std::vector<std::string> first_guess_warnings(const Eigen::MatrixXd& pressures, const ActuatorMask& actuators,
                                              const RoutingSettings& settings, const std::vector<double>& rmse,
                                              const std::vector<std::string>& target_names);

} // namespace fibermold
