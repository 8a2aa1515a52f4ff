#include "export/behaviour_summary.hpp"

#include <algorithm>

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

} // namespace

std::vector<ReportTable> behaviour_tables(const Json& report)
{
  std::vector<ReportTable> out;
  const auto mm = [](const Json& v) { return v.is_number() ? fixed(v.get<double>(), 3) : std::string("–"); };
  if (report["targets"].is_object() && !report["targets"].empty()) {
    ReportTable targets{"Targets: error over the tracking curves and the surface (mm)",
                        {"target", "RMSE before collide", "RMSE after", "change", "max before", "max after",
                         "surface RMSE after", "surface max after"},
                        {}};
    for (const auto& [name, t] : report["targets"].items())
      targets.rows.push_back({name, mm(t["before"]["rmse_mm"]), mm(t["after"]["rmse_mm"]),
                              t["rmse_change_percent"].is_number()
                                  ? fmt::format("{:+.1f} %", t["rmse_change_percent"].get<double>())
                                  : "–",
                              mm(t["before"]["max_error_mm"]), mm(t["after"]["max_error_mm"]),
                              mm(t["after"]["surface_rmse_mm"]), mm(t["after"]["surface_max_error_mm"])});
    out.push_back(std::move(targets));
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
  if (!report.contains("bends") || !report["min_bend_radius_mm"].is_number()) return {};
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
    if (!p.is_object() || !p.contains("translation_mm") || !p["rotation_deg"].is_number()) continue;
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

namespace {

/// The figure of one pose to measure: its value, the key of its stiffness band, its unit and what it is.
struct Measure {
  const Json* pose = nullptr;
  double value = 0;
  const char* band = "";
  const char* unit = "";
  const char* what = "";
};

/// Which figure of which pose to measure (what_to_measure()); none when nothing moves.
Measure measure_of(const Json& poses)
{
  Measure turn, move;
  for (const Json& p : poses) {
    if (!p.is_object() || !p.contains("translation_mm") || !p["rotation_deg"].is_number()) continue;
    if (p.value("asked_rotation_deg", 0.0) != 0 && p["rotation_about_asked_axis_deg"].is_number())
      return {&p, p["rotation_about_asked_axis_deg"].get<double>(), "rotation_about_asked_axis_deg", "°",
              "turn about the axis asked"};
    const double angle = p["rotation_deg"].get<double>();
    const double moved = Eigen::Vector3d(p["translation_mm"][0], p["translation_mm"][1], p["translation_mm"][2]).norm();
    if (angle >= kStaysPut_deg && angle > turn.value) turn = {&p, angle, "rotation_deg", "°", "turn"};
    if (moved >= kStaysPut_mm && moved > move.value) move = {&p, moved, "displacement_mm", " mm", "move"};
  }
  return turn.pose ? turn : move;
}

} // namespace

std::string what_to_measure(const Json& poses, double youngs_modulus)
{
  const Measure m = measure_of(poses);
  if (!m.pose) return {};
  const Json& p = *m.pose;
  std::string text = fmt::format("Measure {}'s {}: {:.1f}{} in the simulation.", p["place"].get<std::string>(), m.what,
                                 m.value, m.unit);
  if (p.contains("sensitivity") && p["sensitivity"].contains(m.band)) {
    const Json& s = p["sensitivity"];
    const Json& v = s[m.band];
    const double percent = s["change_percent"].get<double>();
    const auto value = [&](const char* variation) {
      return fmt::format("{:.1f}{}", v[variation].get<double>(), m.unit);
    };
    text += fmt::format(
        " It hinges on the silicone's stiffness and the muscles' pressure: {} and {} with a silicone {:g} % stiffer "
        "and "
        "softer than the {:.1f} kPa of [material] youngs_modulus, {} and {} at {:g} % less and more pressure. A cast "
        "robot outside these: check the pressure at the muscle first; then the silicone (hang a weight on a strip of "
        "the same pour: E = force × length / (cross-section × stretch), under 20 % stretch; set [material] "
        "youngs_modulus to it and run fibermold again) and the muscle's own contraction at that pressure ([muscle] "
        "rest_strain_slope).",
        value("stiffer"), value("softer"), percent, youngs_modulus / units::kPa, value("less_pressure"),
        value("more_pressure"), percent);
  }
  return wrapped(text, "  ", "  ");
}

} // namespace fibermold
