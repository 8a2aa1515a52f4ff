#include "export/behaviour_summary.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <utility>

#include <Eigen/Core>
#include <fmt/format.h>

#include "core/units.hpp"
#include "core/wrapped_text.hpp"

namespace fibermold {

namespace {

using Json = nlohmann::ordered_json;

// A place that moves less than this, and turns less, stays put: it is not worth comparing.
constexpr double kStaysPut_mm = 0.5, kStaysPut_deg = 5.0;

std::string fixed(double value, int digits) { return fmt::format("{:.{}f}", value, digits); }

/// Whether a pose of collide's report says where it went: a translation [x, y, z] and a rotation.
bool placed(const Json& p)
{
  return p.is_object() && p.contains("translation_mm") && p["translation_mm"].is_array() &&
         p["translation_mm"].size() == 3 && p.contains("rotation_deg") && p["rotation_deg"].is_number() &&
         p.contains("place") && p["place"].is_string();
}

/// The figure of one pose to measure: its value, the key of its sensitivity, its unit and what it is.
struct Measure {
  const Json* pose = nullptr;
  double value = 0;
  const char* band = "";
  const char* unit = "";
  const char* what = "";
};

/// Which figure of which pose to measure (what_to_measure()); none when nothing moves. Its pose points into `poses`.
Measure measure_of(const Json& poses)
{
  Measure turn, move;
  for (const Json& p : poses) {
    if (!placed(p)) continue;
    if (p.value("asked_rotation_deg", 0.0) != 0 && p.contains("rotation_about_asked_axis_deg") &&
        p["rotation_about_asked_axis_deg"].is_number())
      return {&p, p["rotation_about_asked_axis_deg"].get<double>(), "rotation_about_asked_axis_deg", "°",
              "turn about the axis asked"};
    const double angle = p["rotation_deg"].get<double>();
    const double moved = Eigen::Vector3d(p["translation_mm"][0], p["translation_mm"][1], p["translation_mm"][2]).norm();
    if (angle >= kStaysPut_deg && angle > turn.value) turn = {&p, angle, "rotation_deg", "°", "turn"};
    if (moved >= kStaysPut_mm && moved > move.value) move = {&p, moved, "displacement_mm", " mm", "move"};
  }
  return turn.pose ? turn : move;
}

/// What m's figure is under each of kPoseVariations, and by how much (%) they vary the inputs; none when
/// its pose's report has no sensitivity.
std::optional<std::pair<std::array<double, 4>, double>> variations(const Measure& m)
{
  const Json& p = *m.pose;
  if (!p.contains("sensitivity") || !p["sensitivity"].contains(m.band) ||
      !p["sensitivity"].contains("change_percent") || !p["sensitivity"]["change_percent"].is_number())
    return std::nullopt;
  const Json& v = p["sensitivity"][m.band];
  std::array<double, 4> out{};
  for (std::size_t k = 0; k < kPoseVariations.size(); ++k) {
    if (!v.contains(kPoseVariations[k]) || !v[kPoseVariations[k]].is_number()) return std::nullopt;
    out[k] = v[kPoseVariations[k]].get<double>();
  }
  return std::pair{out, p["sensitivity"]["change_percent"].get<double>()};
}

/// m's figure with every muscle at 0 kPa, the body under its weight alone (collide's "unpressurized"):
/// the first thing to compare on the cast robot; empty without it.
std::string unpressurized_text(const Measure& m)
{
  const Json& p = *m.pose;
  if (!p.contains("unpressurized") || !p["unpressurized"].is_object() || !p["unpressurized"].contains(m.band) ||
      !p["unpressurized"][m.band].is_number())
    return {};
  return fmt::format(" Before you pressurize it (every muscle at 0 kPa), held as simulated, its weight alone {} it "
                     "{:.1f}{} in the simulation: compare that first.",
                     m.unit == std::string("°") ? "turns" : "moves", p["unpressurized"][m.band].get<double>(), m.unit);
}

/// The full turn's pressures (collide's "full_turn" pressures_kPa): "lift_px 407 kPa, lift_mx 410 kPa".
std::string full_turn_pressures(const Json& f)
{
  std::string pressures;
  for (const auto& [fiber, kpa] : f["pressures_kPa"].items())
    if (kpa.is_number())
      pressures += fmt::format("{}{} {:.0f} kPa", pressures.empty() ? "" : ", ", fiber, kpa.get<double>());
  return pressures;
}

/// What a pose region that turned short of its angle would take to turn it all (collide's "full_turn"):
/// the pressures, and the turn the simulation reaches there; empty without it (or in a report that
/// lacks a figure of it).
std::string full_turn_text(const Json& p)
{
  if (!p.contains("full_turn") || !p["full_turn"].is_object() || !p.contains("asked_rotation_deg") ||
      !p["asked_rotation_deg"].is_number() || !p.contains("rotation_about_asked_axis_deg") ||
      !p["rotation_about_asked_axis_deg"].is_number())
    return {};
  const Json& f = p["full_turn"];
  const auto number = [&](const char* key) { return f.contains(key) && f[key].is_number(); };
  const auto flag = [&](const char* key) { return f.contains(key) && f[key].is_boolean() && f[key].get<bool>(); };
  if (!number("pressure_scale") || !number("rotation_about_asked_axis_deg") || !f.contains("pressures_kPa") ||
      !f["pressures_kPa"].is_object())
    return {};
  const std::string pressures = full_turn_pressures(f);
  std::string off;
  if (f.contains("off") && f["off"].is_array())
    for (const Json& fiber : f["off"])
      if (fiber.is_string()) off += (off.empty() ? "" : ", ") + fiber.get<std::string>();
  const double turn = f["rotation_about_asked_axis_deg"].get<double>(), asked = p["asked_rotation_deg"].get<double>();
  const double nominal = p["rotation_about_asked_axis_deg"].get<double>();
  const bool at_max = flag("at_max_pressure"), reached = flag("reached");
  std::string text = fmt::format(
      " It is asked to turn {:.1f}°: the optimizer chose these pressures as the best balance of that turn and the "
      "tracking curves' positions{}. At {:.2f} × these pressures ({}{}{}) the simulation turns it {:.1f}°",
      asked, nominal / asked < 0 ? ", and they turn it the other way (check the sign of the pose's axis first)" : "",
      f["pressure_scale"].get<double>(), pressures, off.empty() ? "" : "; " + off + " still off",
      at_max ? ": [muscle] max_pressure for the highest" : "", turn);
  if (reached) return text + ", at the cost of the tracking curves' positions.";
  if (at_max)
    return text + fmt::format(": the muscles do not turn it all the way at the pressure they are rated for ({}add a "
                              "muscle, or use a softer silicone).",
                              off.empty() ? "" : "drive " + off + " too, ");
  return text + ", the nearest to the angle of the pressures tried.";
}

/// report.html's cell for the full turn (collide's "full_turn"): "40.0° at 1.42 × (lift_px 407 kPa, …)".
std::string full_turn_cell(const Json& p)
{
  if (full_turn_text(p).empty()) return "–";
  const Json& f = p["full_turn"];
  const std::string pressures = full_turn_pressures(f);
  const bool flagged = f.contains("at_max_pressure") && f["at_max_pressure"].is_boolean();
  return fmt::format("{:.1f}° at {:.2f} × ({}){}", f["rotation_about_asked_axis_deg"].get<double>(),
                     f["pressure_scale"].get<double>(), pressures,
                     flagged && f["at_max_pressure"].get<bool>() ? ", max_pressure" : "");
}

/// The command that shows the full turn's figure (collide's "full_turn"): the robot as built at those
/// pressures, the target's regions said as README.txt says them; empty without it.
std::string full_turn_command(const Json& p, const std::string& as_built_command)
{
  if (full_turn_text(p).empty()) return {};
  std::string command = as_built_command;
  for (const auto& [fiber, kpa] : p["full_turn"]["pressures_kPa"].items())
    if (kpa.is_number())
      command += fmt::format(" --pressure {}={:.1f}", fiber, std::floor(10 * kpa.get<double>()) / 10);
  return "  To see it turn so in the simulation, run from the design's folder:\n      " + command + "\n";
}

} // namespace

std::vector<ReportTable> behaviour_tables(const Json& collide_report)
{
  Json report = collide_report; // not const: a key missing from another's report reads as null, which throws
  std::vector<ReportTable> out;
  const auto mm = [](const Json& v) { return v.is_number() ? fixed(v.get<double>(), 3) : std::string("–"); };
  if (report["targets"].is_object() && !report["targets"].empty()) {
    ReportTable targets{"Targets: error over the tracking curves and the surface (mm)",
                        {"target", "RMSE before collide", "RMSE after", "change", "max before", "max after",
                         "surface RMSE after", "surface max after"},
                        {}};
    // The turn's error where a tracking curve's orientation is tracked (a twist shows there, not in mm).
    bool turns = false;
    for (const auto& [name, t] : report["targets"].items())
      turns = turns || (t["after"].is_object() && t["after"].contains("orientation_rms_deg"));
    if (turns)
      targets.header.insert(targets.header.end(), {"turn's error before (° RMS)", "turn's error after (° RMS)"});
    const auto degrees = [](const Json& v) { return v.is_number() ? fixed(v.get<double>(), 1) : std::string("–"); };
    for (const auto& [name, t] : report["targets"].items()) {
      targets.rows.push_back({name, mm(t["before"]["rmse_mm"]), mm(t["after"]["rmse_mm"]),
                              t["rmse_change_percent"].is_number()
                                  ? fmt::format("{:+.1f} %", t["rmse_change_percent"].get<double>())
                                  : "–",
                              mm(t["before"]["max_error_mm"]), mm(t["after"]["max_error_mm"]),
                              mm(t["after"]["surface_rmse_mm"]), mm(t["after"]["surface_max_error_mm"])});
      if (turns)
        targets.rows.back().insert(targets.rows.back().end(), {degrees(t["before"]["orientation_rms_deg"]),
                                                               degrees(t["after"]["orientation_rms_deg"])});
    }
    out.push_back(std::move(targets));
    // README.txt's figure to measure on the cast robot, per target, and what it hinges on.
    ReportTable check{"Checking the cast robot: the figure to measure",
                      {"target", "figure", "simulated", "silicone stiffer", "silicone softer", "less pressure",
                       "more pressure", "unpressurized (its weight)", "the whole angle asked"},
                      {}};
    for (const auto& [name, t] : report["targets"].items()) {
      const Json poses = t.value("poses", Json::array()); // m points into it
      const Measure m = measure_of(poses);
      if (!m.pose) continue;
      std::vector<std::string> row{name, fmt::format("{}: {}", (*m.pose)["place"].get<std::string>(), m.what),
                                   fmt::format("{:.1f}{}", m.value, m.unit)};
      const auto varied = variations(m);
      for (std::size_t k = 0; k < kPoseVariations.size(); ++k)
        row.push_back(varied ? fmt::format("{:.1f}{}", varied->first[k], m.unit) : "–");
      const Json& p = *m.pose;
      row.push_back(p.contains("unpressurized") && p["unpressurized"].contains(m.band) &&
                            p["unpressurized"][m.band].is_number()
                        ? fmt::format("{:.1f}{}", p["unpressurized"][m.band].get<double>(), m.unit)
                        : "–");
      row.push_back(full_turn_cell(p));
      if (varied)
        check.title = fmt::format("Checking the cast robot: the figure to measure, and with the silicone's stiffness "
                                  "or the pressure {:g} % off",
                                  varied->second);
      check.rows.push_back(std::move(row));
    }
    if (!check.rows.empty()) out.push_back(std::move(check));
  }
  ReportTable collisions{"Collisions", {"between", "clearance before (mm)", "at (mm)"}, {}};
  for (const Json& c : report["collisions"]) {
    std::string between;
    for (const Json& n : c["between"]) between += (between.empty() ? "" : " and ") + n.get<std::string>();
    std::string at;
    for (const Json& v : c["at_mm"])
      at += (at.empty() ? "" : ", ") + (v.is_number() ? fixed(v.get<double>(), 1) : std::string("–"));
    collisions.rows.push_back({between, mm(c["clearance_mm"]), "(" + at + ")"});
  }
  if (collisions.rows.empty()) collisions.rows.push_back({"none: every fiber was clear", "", ""});
  out.push_back(std::move(collisions));
  ReportTable moves{fmt::format("Collide: smallest clearance {} → {} mm (asked {} mm); {} round(s){}",
                                mm(report["smallest_clearance_mm"].value("before", Json())),
                                mm(report["smallest_clearance_mm"].value("after", Json())), mm(report["clearance_mm"]),
                                report["rounds"].get<int>(),
                                report["reoptimized"].get<bool>() ? ", optimized again" : ""),
                    {"fiber", "largest control point move (mm)", "largest tangent change (mm)"},
                    {}};
  for (const auto& [fiber, m] : report["moves_mm"].items()) {
    double point = 0, tangent = 0;
    for (const Json& v : m["points"]) point = std::max(point, v.is_number() ? v.get<double>() : 0.0);
    for (const Json& v : m["tangents"]) tangent = std::max(tangent, v.is_number() ? v.get<double>() : 0.0);
    moves.rows.push_back({fiber, fixed(point, 3), fixed(tangent, 3)});
  }
  out.push_back(std::move(moves));
  // Each fiber's tightest bend as it will be cast, against the muscle's limit.
  ReportTable bends{fmt::format("Bend radius: each fiber's smallest, as built (the muscle takes {} mm)",
                                mm(report["min_bend_radius_mm"])),
                    {"fiber", "smallest bend radius (mm)", "at (mm)", "along the fiber (mm)"},
                    {}};
  for (const auto& [fiber, b] : report["bends"].items()) {
    if (!b.contains("min_bend_radius_mm")) {
      bends.rows.push_back({fiber, "straight", "", ""});
      continue;
    }
    std::string at;
    for (const Json& v : b["at_mm"]) at += (at.empty() ? "" : ", ") + mm(v);
    bends.rows.push_back({fiber, mm(b["min_bend_radius_mm"]), "(" + at + ")", mm(b["along_mm"])});
  }
  if (!bends.rows.empty()) out.push_back(std::move(bends));
  return out;
}

std::string muscle_bends_text(const Json& report)
{
  if (!report.contains("bends") || !report.contains("min_bend_radius_mm") || !report["min_bend_radius_mm"].is_number())
    return {};
  std::string text = "\n";
  text += wrapped(fmt::format("The muscles take bends no tighter than {:.1f} mm in radius ([muscle] min_bend_radius); "
                              "the grooves follow the routes, so lay each muscle along its groove without kinking it. "
                              "Each route's tightest bend:",
                              report["min_bend_radius_mm"].get<double>()),
                  "", "");
  for (const auto& [fiber, b] : report["bends"].items())
    text += b.contains("min_bend_radius_mm")
                ? fmt::format("  {}: {:.1f} mm, {:.1f} mm along it\n", fiber, b["min_bend_radius_mm"].get<double>(),
                              b["along_mm"].get<double>())
                : fmt::format("  {}: straight\n", fiber);
  return text;
}

std::string poses_to_compare(const Json& poses)
{
  std::string out;
  for (const Json& p : poses) {
    if (!placed(p) || !p.contains("rotation_axis")) continue;
    const Eigen::Vector3d t(p["translation_mm"][0], p["translation_mm"][1], p["translation_mm"][2]);
    const double turn = p["rotation_deg"].get<double>();
    if (t.norm() < kStaysPut_mm && turn < kStaysPut_deg) continue;
    // Where it is on the robot: a region's centre at rest, or the curve's point (older reports: the name only).
    const std::string where =
        p.contains("rest_mm")
            ? fmt::format(" (at {} at rest{})",
                          format_mm(Eigen::Vector3d(p["rest_mm"][0], p["rest_mm"][1], p["rest_mm"][2]) * units::mm),
                          p.contains("nodes") ? fmt::format(": the centre of its {} nodes", p["nodes"].get<int>()) : "")
            : "";
    std::string line = fmt::format(
        "{}{}: moves {:.1f} mm ({:.1f}, {:.1f}, {:.1f}) and turns {:.1f}° about ({:.2f}, {:.2f}, {:.2f})",
        p["place"].get<std::string>(), where, t.norm(), t.x(), t.y(), t.z(), turn, p["rotation_axis"][0].get<double>(),
        p["rotation_axis"][1].get<double>(), p["rotation_axis"][2].get<double>());
    if (p.contains("rotation_about_asked_axis_deg") && p.contains("asked_rotation_deg"))
      line += fmt::format("; {:.1f}° about the axis asked (asked {:.1f}°)",
                          p["rotation_about_asked_axis_deg"].get<double>(), p["asked_rotation_deg"].get<double>());
    out += wrapped(line, "    ", "      ");
  }
  return out.empty()
             ? fmt::format("    nothing moves more than {} mm or turns more than {}°\n", kStaysPut_mm, kStaysPut_deg)
             : out;
}

std::string what_to_measure(const Json& poses, double youngs_modulus, bool beyond_max_pressure,
                            const std::string& as_built_command)
{
  const Measure m = measure_of(poses);
  if (!m.pose) return {};
  const Json& p = *m.pose;
  // Where it is at rest, and the axis of the turn (the asked one for a pose region) or the move's direction.
  const auto vec = [&](const char* key) {
    if (!p.contains(key) || !p[key].is_array() || p[key].size() != 3) return std::string("?");
    const auto coordinate = [&](int k) { return std::round(100 * p[key][k].get<double>()) / 100 + 0.0; }; // no -0.00
    return fmt::format("({:.2f}, {:.2f}, {:.2f})", coordinate(0), coordinate(1), coordinate(2));
  };
  const bool asked = m.band == std::string("rotation_about_asked_axis_deg");
  const std::string at = p.contains("rest_mm") ? fmt::format(" (at {} mm at rest)", vec("rest_mm")) : "";
  const std::string about = m.band == std::string("displacement_mm") ? ""
                            : !asked                                 ? " about " + vec("rotation_axis")
                            : p.contains("asked_axis")               ? " about the axis asked, " + vec("asked_axis")
                                                                     : " about the axis asked";
  std::string text = fmt::format("Measure {}'s {}{}{}: {:.1f}{} in the simulation.", p["place"].get<std::string>(),
                                 asked ? "turn" : m.what, at, about, m.value, m.unit);
  if (m.unit == std::string("°") && p.contains("nodes") && p["nodes"].is_number())
    text += fmt::format(" That is the best rigid fit of its {} nodes (the whole face); a point of it, such as a "
                        "tracking curve's end, may turn a few degrees more or less.",
                        p["nodes"].get<int>());
  // How, with what a lab has (a new user asked): the turn seen along its axis, the move from square to it.
  text += m.unit == std::string("°")
              ? " To measure it, photograph the robot at rest and pressurized from along that axis, the camera held "
                "still, and take the angle between the same straight edge there in the two photographs."
              : " To measure it, photograph the robot at rest and pressurized from the side, square to the move, "
                "beside a ruler, the camera held still.";
  text += unpressurized_text(m);
  if (asked) text += full_turn_text(p);
  if (const auto varied = variations(m)) {
    const auto& [v, percent] = *varied;
    const auto value = [&](std::size_t k) { return fmt::format("{:.1f}{}", v[k], m.unit); };
    const double lo = std::min({m.value, v[0], v[1], v[2], v[3]}), hi = std::max({m.value, v[0], v[1], v[2], v[3]});
    // The modulus the simulation used, to the pascal: the value `simulate --as-built` prints (rounded
    // to 3 figures it read as another, 45100 against 45129 Pa, to a new user).
    const double e = youngs_modulus;
    text += fmt::format(
        " With the least certain inputs {0:g} % off: {1} and {2} with the silicone {0:g} % stiffer and softer than "
        "[material] youngs_modulus = {3:.0f} Pa, {4} and {5} with every pressure {0:g} % lower and higher{9}. Outside "
        "{6:.1f}–{7:.1f}{8}, check first the pressure at the muscle; then the silicone: stretch a strip of the same "
        "pour (about 10 × 3 mm across) by 20–50 % under a hanging weight, E = 3 × force / (cross-section × (λ − "
        "1/λ²)) in Pa, with the force in N (grams × 0.00981), the unstretched cross-section in m² (mm² × 10⁻⁶) and λ "
        "the stretched length over the length; then the muscle's contraction at that pressure ([muscle] "
        "rest_strain_slope). Set what you measured in the design before designing the next robot: a run routes the "
        "muscles for it and makes other molds, so give it a new build folder (--build-dir) and keep this one. To "
        "predict this robot with what you measured, run from the design's folder (it keeps the routes and pressures "
        "these molds were made for):",
        percent, value(0), value(1), e, value(2), value(3), lo, hi, m.unit,
        beyond_max_pressure ? " (the higher is above [muscle] max_pressure for a muscle: a figure to compare, not a "
                              "pressure to drive it at)"
                            : "");
    return wrapped(text, "  ", "  ") + "      " + as_built_command + "\n" + full_turn_command(p, as_built_command);
  }
  return wrapped(text, "  ", "  ");
}

} // namespace fibermold
