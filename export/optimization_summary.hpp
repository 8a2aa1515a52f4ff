#pragma once
// What the optimization reached, as the export stage shows it, from optimize/report.json and
// optimize/history.csv: its warnings (report.html's banner and a paragraph of README.txt), each
// target's error at the start and the end with the fibers' pressures, and the objective per iteration.

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "export/report_html.hpp"

namespace fibermold {

/// Whether optimize/report.json is that of a run that optimized targets (not one with optimize
/// disabled, or without targets).
bool optimized_targets(const nlohmann::ordered_json& report);

/// The optimization's warnings (a target far from reached, a muscle at its limit, no convergence).
std::vector<std::string> optimization_warnings(const nlohmann::ordered_json& report);

/// README.txt's paragraph with the warnings, wrapped at 100 columns; empty without any.
std::string optimization_warnings_text(const nlohmann::ordered_json& report);

/// How the optimization ended: per target the RMSE at the start, of the first guess at its best
/// pressures (report.json's first_guess: what the optimized routes must beat) and at the end; where a
/// tracking curve's orientation is tracked, the turn's RMS error (°) at the same three; how much of
/// the start's RMSE was reached, the turns of its poses ("54.1° of 60.0° (pose[1])") and each fiber's
/// pressure.
ReportTable optimization_table(const nlohmann::ordered_json& report);

/// The objective and its distance term per iteration (optimize/history.csv's text); none when the
/// file lacks those columns or rows.
std::optional<ReportPlot> optimization_history(const std::string& history_csv);

} // namespace fibermold
