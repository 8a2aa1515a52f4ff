#pragma once
// What report.html shows of the mold parts, from molds/report.json and the manifest's parts: the
// table of the parts (files, what each carries engraved, its checks) and which hole is which.

#include <string>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "export/report_html.hpp"

namespace fibermold {

/// The parts table: per part of the manifest its files, what it carries engraved ("“WALKING-ROBOT S1
/// LOWER” (side, 8 mm) · “IN” (end, 5 mm)", or "none"), triangles, volume, thinnest wall, whether it
/// fits the printer lying flat, and whether it passed its checks.
ReportTable parts_table(const nlohmann::ordered_json& parts);

/// Which hole is which: each sprue and vent of a shot (its "fill" in molds/report.json) drawn as a
/// line through its half, from where it meets the cavity out along `pull` (a sprue from below: down
/// through the lower half), named, the sprue orange and the vents cyan; the parts of the shot sit at
/// `offset`, its upper half 1.5 × `height` further along the pull. Shown for shot 1, hidden for shot 2.
std::vector<ReportLine> port_lines(const nlohmann::ordered_json& fill, const std::string& shot,
                                   const Eigen::Vector3d& pull, double height, const Eigen::Vector3d& offset);

} // namespace fibermold
