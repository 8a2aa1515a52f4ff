#include "export/optimization_summary.hpp"

#include <algorithm>
#include <sstream>

#include <fmt/format.h>

#include "core/wrapped_text.hpp"

namespace fibermold {

using Json = nlohmann::ordered_json;

bool optimized_targets(const Json& report)
{
  return report.value("optimized", false) && report.contains("targets") && report["targets"].is_object() &&
         !report["targets"].empty();
}

std::vector<std::string> optimization_warnings(const Json& report)
{
  std::vector<std::string> out;
  for (const Json& w : report.value("warnings", Json::array()))
    if (w.is_string()) out.push_back(w.get<std::string>());
  return out;
}

std::string optimization_warnings_text(const Json& report)
{
  std::string text;
  for (const std::string& w : optimization_warnings(report)) text += wrapped(w, "  - ", "    ");
  return text.empty() ? text
                      : "\nThe optimization warned (report.html gives its figures); the cast robot will do what the\n"
                        "simulation does, not what was asked:\n" +
                            text;
}

namespace {

/// A pose target's turns: "54.1° of 60.0° (pose[1])"; empty for a target without turns.
std::string turns(const Json& target)
{
  std::string out;
  if (target.contains("poses") && target["poses"].is_array())
    for (const Json& p : target["poses"])
      if (p.is_object() && p.contains("asked_rotation_deg") && p["asked_rotation_deg"].is_number() &&
          p.contains("rotation_about_asked_axis_deg") && p["rotation_about_asked_axis_deg"].is_number())
        out += fmt::format("{}{:.1f}° of {:.1f}° ({})", out.empty() ? "" : "; ",
                           p["rotation_about_asked_axis_deg"].get<double>(), p["asked_rotation_deg"].get<double>(),
                           p.value("place", std::string("?")));
  return out;
}

} // namespace

ReportTable optimization_table(const Json& report)
{
  const auto number = [](const Json& j, const char* key, int digits, const std::string& unit = "") {
    return j.is_object() && j.contains(key) && j[key].is_number()
               ? fmt::format("{:.{}f}", j[key].get<double>(), digits) + unit
               : std::string("–");
  };
  // Where the optimized routes matched the targets less well than the first guess, the first guess is
  // what the end is: said in the title, as "end" alone read as the optimizer's (a new user's starfish).
  const bool kept_first_guess = report.value("kept", std::string()) == "first guess";
  ReportTable t{fmt::format("Optimization: {} after {} iterations ({}){}",
                            report.value("termination", std::string("?")), report.value("iterations", 0),
                            report.value("message", std::string()),
                            kept_first_guess ? "; its routes matched the targets less well than the first guess, "
                                               "which is kept: the end is the first guess at its best pressures"
                                             : ""),
                {"target", "RMSE at the start: the first guess at half max_pressure (mm)",
                 "RMSE of the first guess at its best pressures (mm)", "RMSE at the end (mm)"},
                {}};
  const Json& targets = report["targets"];
  const Json guesses = report.contains("first_guess") && report["first_guess"].is_object()
                           ? report["first_guess"].value("targets", Json::object())
                           : Json::object();
  bool any_turn = false, any_orientation = false;
  for (const auto& [name, target] : targets.items()) {
    any_turn = any_turn || !turns(target).empty();
    any_orientation = any_orientation || target.contains("orientation_rms_deg");
  }
  if (any_orientation)
    for (const char* when : {"at the start", "of the first guess", "at the end"})
      t.header.push_back(fmt::format("turn's error {} (° RMS)", when));
  t.header.push_back("reached: 1 − end / start RMSE");
  // Beside it, what the routes gained over the first guess at its own best pressures: "reached 81 %" alone
  // read as the optimizer's doing where the pressures did most of it (a new user's finger: 8.37 mm at
  // the start, 1.66 mm for the first guess at its best pressure, 1.59 mm at the end: 4 %).
  const bool any_guess = !guesses.empty();
  if (any_guess) t.header.push_back("the routes' gain: 1 − end / first guess RMSE");
  if (any_turn) t.header.push_back("turn reached");
  std::vector<std::string> fibers; // every target's report names every fiber's pressure
  const Json& first = targets.begin().value();
  if (first.contains("pressure_kPa") && first["pressure_kPa"].is_object())
    for (const auto& [fiber, p] : first["pressure_kPa"].items()) {
      fibers.push_back(fiber);
      t.header.push_back(fiber + " (kPa)");
    }
  for (const auto& [name, target] : targets.items()) {
    const Json start = target.value("start", Json::object());
    const Json guess = guesses.is_object() ? guesses.value(name, Json::object()) : Json::object();
    std::vector<std::string> row{name, number(start, "rmse_mm", 3), number(guess, "rmse_mm", 3),
                                 number(target, "rmse_mm", 3)};
    if (any_orientation)
      for (const Json* j : {&start, &guess, &target}) row.push_back(number(*j, "orientation_rms_deg", 1));
    row.push_back(number(target, "reached_percent", 0, " %"));
    if (any_guess) {
      const bool both = guess.contains("rmse_mm") && guess["rmse_mm"].is_number() && target.contains("rmse_mm") &&
                        target["rmse_mm"].is_number() && guess["rmse_mm"].get<double>() > 0;
      row.push_back(
          both ? fmt::format("{:.0f} %", 100 * (1 - target["rmse_mm"].get<double>() / guess["rmse_mm"].get<double>()))
               : "–");
    }
    if (any_turn) row.push_back(turns(target).empty() ? "–" : turns(target));
    for (const std::string& f : fibers)
      row.push_back(number(target.value("pressure_kPa", Json::object()), f.c_str(), 1));
    t.rows.push_back(std::move(row));
  }
  return t;
}

std::optional<ReportPlot> optimization_history(const std::string& history_csv)
{
  std::istringstream lines(history_csv);
  std::string header;
  std::getline(lines, header);
  std::vector<std::string> columns;
  std::istringstream names(header);
  for (std::string c; std::getline(names, c, ',');) columns.push_back(c);
  const auto column = [&](const std::string& name) {
    return std::find(columns.begin(), columns.end(), name) - columns.begin();
  };
  const auto iteration = column("iteration"), objective = column("objective"), distance = column("distance");
  if (std::max({iteration, objective, distance}) >= std::ssize(columns)) return std::nullopt;
  ReportPlot plot{"Optimization", "iteration", "objective", {{"objective", {}}, {"distance term", {}}}, true, true};
  for (std::string line; std::getline(lines, line);) {
    std::vector<double> v;
    std::istringstream cells(line);
    for (std::string cell; std::getline(cells, cell, ',');) v.push_back(std::strtod(cell.c_str(), nullptr));
    if (std::ssize(v) < std::ssize(columns)) continue;
    plot.series[0].second.emplace_back(v[iteration], v[objective]);
    plot.series[1].second.emplace_back(v[iteration], v[distance]);
  }
  if (plot.series[0].second.empty()) return std::nullopt;
  return plot;
}

} // namespace fibermold
