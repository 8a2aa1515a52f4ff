#include "optimize/optimization_ending.hpp"

#include <algorithm>
#include <string_view>

#include <fmt/format.h>

#include "core/units.hpp"
#include "optimize/bend_radius.hpp"

namespace fibermold {

namespace {
/// Whether target t has a muscle and every one of its muscles is at 0 (within `margin`).
bool every_muscle_off(const Eigen::MatrixXd& p, const ActuatorMask& actuators, Eigen::Index t, double margin)
{
  bool any = false, all_off = true;
  for (Eigen::Index f = 0; f < p.cols(); ++f)
    if (actuators(t, f)) {
      any = true;
      all_off = all_off && p(t, f) <= margin;
    }
  return any && all_off;
}
/// "tip turned 28.0° of the 40.0° asked (70 %)" (with `note` inside the brackets), after a comma
/// where `list` has one already.
void append_turn(std::string& list, const AngleReach& a, std::string_view note = "")
{
  list += fmt::format("{}{} turned {:.1f}° of the {:.1f}° asked ({:.0f} %{})", list.empty() ? "" : ", ", a.place,
                      a.reached / units::degree, a.asked / units::degree, 100 * a.reached / a.asked, note);
}

/// Target t's regions that turned between 1 − kFarFromReached and kShortOfTurn of their angles: one
/// warning naming them and the muscles' pressures, with what holds the turn back.
void short_of_turns(Eigen::Index t, const std::vector<AngleReach>& turns, const Eigen::MatrixXd& p,
                    const ActuatorMask& actuators, double max_pressure, double margin, const std::string& target,
                    std::vector<std::string>& warnings)
{
  std::string regions;
  for (const AngleReach& a : turns)
    if (a.asked != 0 && a.reached / a.asked >= 1 - kFarFromReached && a.reached / a.asked < kShortOfTurn)
      append_turn(regions, a);
  if (regions.empty()) return;
  std::string pressures;
  bool at_max = false;
  for (Eigen::Index f = 0; f < p.cols(); ++f)
    if (actuators(t, f)) {
      pressures += fmt::format("{}{:.0f}", pressures.empty() ? "" : ", ", p(t, f) / units::kPa);
      at_max = at_max || p(t, f) >= max_pressure - margin;
    }
  warnings.push_back(fmt::format(
      "target {} is short of its turn: {}, its muscles at {} kPa of [muscle] max_pressure = {:.0f} kPa; {}", target,
      regions, pressures, max_pressure / units::kPa,
      at_max ? "a muscle is at max_pressure: raise it if the muscle takes it, add a muscle, or use a softer material"
             : "with pressure to spare, the optimizer weighed the turn against the tracking curves' positions (a "
               "muscle that turns the region further moves the curves away from where the target puts them, e.g. by "
               "shortening the body): raise the tracking curves' weight_orientation to favour the turn, or ask for "
               "the translation that the turn brings"));
}

} // namespace

std::vector<std::string> first_guess_warnings(const Eigen::MatrixXd& pressures, const ActuatorMask& actuators,
                                              const RoutingSettings& settings, const std::vector<double>& rmse,
                                              const std::vector<std::string>& target_names)
{
  std::vector<std::string> out;
  const double margin = settings.pressure_margin * settings.max_pressure;
  for (Eigen::Index t = 0; t < pressures.rows(); ++t)
    if (every_muscle_off(pressures, actuators, t, margin))
      out.push_back(fmt::format(
          "target {}: the first guess's muscles do best at 0 kPa (at most {:.1f} kPa): pressurized, the routes as "
          "drawn take the body further from the target than its weight and how it is held do alone (tracking-curve "
          "RMSE {:.2f} mm at those pressures). Either its weight already moves it as far as the target asks, or "
          "further (check [material] gravity and the [[fixed]] regions against how it will be used), or its muscles "
          "bend it away from the target (a muscle bends the body toward the side it runs on)",
          target_names[t], margin / units::kPa, t < std::ssize(rmse) ? rmse[t] / units::mm : 0.0));
  return out;
}

OptimizationEnding optimization_ending(const RoutingResult& result, const ActuatorMask& actuators,
                                       const RoutingSettings& settings, const std::vector<TargetErrors>& before,
                                       const std::vector<TargetErrors>& after,
                                       const std::vector<std::vector<AngleReach>>& angles,
                                       const std::vector<std::string>& target_names,
                                       const std::vector<std::string>& fiber_names)
{
  OptimizationEnding e;
  const Eigen::MatrixXd& p = result.routing.pressures;
  const double max_pressure = settings.max_pressure, margin = settings.pressure_margin * max_pressure;
  // At the iteration limit the user's remedy is one key: say which (a new user's run ended there and the warning
  // named no way on).
  if (!result.converged)
    e.warnings.push_back(
        fmt::format("the optimizer stopped before converging ({}: {}); the routes are the best it found{}",
                    choice_name(result.termination), result.message,
                    result.termination == Termination::iteration_limit
                        ? ". A longer run may do better: raise [optimize] max_iterations (the optimization starts over)"
                        : ""));
  for (Eigen::Index t = 0; t < p.rows(); ++t) {
    // Every muscle of the target off: the optimized robot is the body unactuated, under its weight
    // and held as the design holds it (a forces target's loads only made its shape). Said once for the target, with
    // what to check: a body that sags where the target asks for it to bend (held the wrong way, or gravity along the
    // wrong axis) is "met" with its muscles off (a 90 mm finger of Ecoflex 00-30 held level sags 54 mm).
    const bool all_off = every_muscle_off(p, actuators, t, margin);
    if (all_off)
      e.warnings.push_back(fmt::format(
          "target {}: every muscle of it ends at 0 kPa (at most {:.1f} kPa, the pressure barrier's margin): the "
          "optimized robot is the body unactuated, which its weight and how it is held alone bring to a "
          "tracking-curve RMSE of {:.2f} mm. If the body is not to move that way by itself, check [material] gravity "
          "and the [[fixed]] regions against how it will be used; else it needs no muscle for this target",
          target_names[t], margin / units::kPa,
          t < static_cast<Eigen::Index>(after.size()) ? after[t].rmse / units::mm : 0.0));
    for (Eigen::Index f = 0; f < p.cols(); ++f) {
      if (!actuators(t, f)) continue;
      const bool at_max = p(t, f) >= max_pressure - margin, at_zero = p(t, f) <= margin;
      if (!at_max && !at_zero) continue;
      e.limits.push_back({static_cast<int>(t), static_cast<int>(f), p(t, f), at_max});
      if (at_zero && all_off) continue; // said for the target
      const std::string& fiber = fiber_names[f];
      const std::string& target = target_names[t];
      e.warnings.push_back(
          at_max
              ? fmt::format(
                    "target {}: fiber {} ends at {:.1f} kPa, at its limit, [muscle] max_pressure = {:.0f} kPa (within "
                    "the {:.0f} % where the pressure barrier holds it): more of the target needs more than the muscle "
                    "can give",
                    target, fiber, p(t, f) / units::kPa, max_pressure / units::kPa, 100 * settings.pressure_margin)
              : fmt::format(
                    "target {}: fiber {} ends at {:.1f} kPa: the optimizer turned it off, it does not help this target "
                    "from where its route ended (if it is not meant to, list the fibers that are in the target's "
                    "actuators, and this is not said)",
                    target, fiber, p(t, f) / units::kPa));
    }
  }
  for (std::size_t f = 0; f < result.routing.routes.size() && settings.min_bend_radius > 0; ++f) {
    const Route& route = result.routing.routes[f];
    const SmallestBend b = smallest_bend(HermiteSpline(route.points, route.tangents));
    if (!(b.radius <= (1 + kBendAtLimit) * settings.min_bend_radius)) continue;
    e.bends.push_back({static_cast<int>(f), b.radius, b.where});
    e.warnings.push_back(fmt::format(
        "fiber {} bends through {:.2f} mm at {}, {:.1f} mm along it: at its limit, [muscle] min_bend_radius = {:.2f} "
        "mm (within {:.0f} %): there the bend radius, not the targets, decides the route",
        fiber_names[f], b.radius / units::mm, format_mm(b.where), b.arc_length / units::mm,
        settings.min_bend_radius / units::mm, 100 * kBendAtLimit));
  }
  for (std::size_t t = 0; t < before.size(); ++t) {
    TargetReach r{before[t].rmse, after[t].rmse, before[t].rmse > 0 ? 1 - after[t].rmse / before[t].rmse : 1.0};
    e.targets.push_back(r);
    std::string how_far;
    const std::vector<AngleReach> turns = t < angles.size() ? angles[t] : std::vector<AngleReach>{};
    for (const AngleReach& a : turns)
      if (a.asked != 0 && a.reached / a.asked < 1 - kFarFromReached)
        append_turn(how_far, a,
                    a.reached / a.asked < 0
                        ? ": the other way; check the sign of the pose's axis against its translation"
                        : "");
    short_of_turns(static_cast<Eigen::Index>(t), turns, p, actuators, max_pressure, margin, target_names[t],
                   e.warnings);
    const bool asks_turns = std::any_of(turns.begin(), turns.end(), [](const AngleReach& a) { return a.asked != 0; });
    if (!asks_turns && before[t].rmse > 0 && after[t].rmse > kFarFromReached * before[t].rmse)
      how_far = fmt::format("{:.0f} % of the way (tracking-curve RMSE {:.2f} → {:.2f} mm)", 100 * r.reached,
                            r.start_rmse / units::mm, r.end_rmse / units::mm);
    if (how_far.empty()) continue; // nothing to reach, or reached
    bool limited = false, bent = false;
    for (const PressureLimit& l : e.limits) limited = limited || (l.target == static_cast<int>(t) && l.at_max);
    for (const BendLimit& b : e.bends) bent = bent || actuators(static_cast<Eigen::Index>(t), b.fiber);
    e.warnings.push_back(fmt::format(
        "target {} is far from reached: {}; {}{}", target_names[t], how_far,
        limited ? "its muscles are at max_pressure: raise [muscle] max_pressure if the muscle takes it, add a muscle, "
                  "or use a softer material"
                : "add a muscle, start the routes elsewhere, or use a softer material; raise [optimize] "
                  "max_iterations if the optimizer stopped at its limit",
        bent ? "; a muscle of it is at its smallest bend radius: lower [muscle] min_bend_radius only if the muscle "
               "takes a tighter bend"
             : ""));
  }
  return e;
}

} // namespace fibermold
