#pragma once
// How the robot does its job once its fibers were moved apart, as the export stage shows it, from
// collide/report.json: each target's error before and after, the collisions and the moves that
// resolved them, each fiber's tightest bend, and what to compare on the cast robot.

#include <array>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "export/report_html.hpp"

namespace fibermold {

/// How far collide varies the least certain inputs to show how much a pose hinges on them: the cast
/// silicone's Young's modulus (sources disagree by 2–3×, docs/design-file.md) and the muscles' pressure
/// (the gauge's, and the muscle's own contraction at it).
inline constexpr double kSensitivityChange = 0.1;
/// The variations as collide's report names them (stages/target_poses.hpp's pose_report), in order: the
/// silicone stiffer and softer by kSensitivityChange, every pressure lower and higher by it.
inline constexpr std::array<const char*, 4> kPoseVariations{"stiffer", "softer", "less_pressure", "more_pressure"};

/// report.html's tables: the targets' errors, the figure to measure on the cast robot per target (as
/// what_to_measure() chooses it) with its sensitivity, the collisions, the control points' moves and
/// each fiber's smallest bend radius as built.
std::vector<ReportTable> behaviour_tables(const nlohmann::ordered_json& collide_report);

/// README.txt's paragraph on the muscles' bends: lay each muscle along its groove without kinking it,
/// and each route's tightest bend. Empty when the report gives no bends.
std::string muscle_bends_text(const nlohmann::ordered_json& collide_report);

/// What to compare on the cast robot for one target (its "poses" in collide's report): where its
/// regions and the tracking curves' ends went, one wrapped line each, leaving out the places that
/// move less than 0.5 mm and turn less than 5° (a curve's clamped first point).
std::string poses_to_compare(const nlohmann::ordered_json& poses);

/// README.txt's one figure to check a target by (its "poses" in collide's report): a pose region's turn
/// about the axis asked; else the largest turn over 5°; else the largest move over 0.5 mm; with what it
/// is with the silicone stiffer and softer and the pressures lower and higher (each pose's "sensitivity"),
/// and what to check when the cast robot falls outside. `youngs_modulus` (Pa): the [material] value
/// simulated; `beyond_max_pressure`: whether the higher pressure is above [muscle] max_pressure for a
/// muscle (it is said so); `as_built_command`: the command that simulates the cast robot again with the
/// values measured (`fibermold simulate … --as-built --target …`). Empty when nothing moves that much.
std::string what_to_measure(const nlohmann::ordered_json& poses, double youngs_modulus, bool beyond_max_pressure,
                            const std::string& as_built_command);

} // namespace fibermold
