#include "export/mold_parts_summary.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "core/units.hpp"

namespace fibermold {

using Json = nlohmann::ordered_json;

namespace {

std::string engraved_text(const Json& labels)
{
  std::vector<std::string> out;
  for (const Json& l : labels)
    out.push_back(fmt::format("“{}” ({}, {:g} mm)", l["text"].get<std::string>(), l["face"].get<std::string>(),
                              l["height_mm"].get<double>()));
  return out.empty() ? "none" : fmt::format("{}", fmt::join(out, " · "));
}

} // namespace

ReportTable parts_table(const Json& parts)
{
  const auto fixed = [](const Json& v, int digits) { return fmt::format("{:.{}f}", v.get<double>(), digits); };
  ReportTable table{
      "Mold parts",
      {"part", "files", "engraved", "triangles", "volume (mL)", "thinnest wall (mm)", "fits the printer", "checks"},
      {}};
  for (const Json& p : parts) {
    std::string files;
    for (const Json& f : p["files"]) files += (files.empty() ? "" : ", ") + f.get<std::string>();
    table.rows.push_back({p["name"], files, engraved_text(p["labels"]), std::to_string(p["triangles"].get<long>()),
                          fixed(p["volume_mL"], 2), fixed(p["min_wall_mm"], 2),
                          p["fits_printer_as_placed"].get<bool>() ? "lying flat" : "turned",
                          p["checks_passed"].get<bool>() ? "passed" : "FAILED"});
  }
  return table;
}

std::vector<ReportLine> port_lines(const Json& fill, const std::string& shot, const Eigen::Vector3d& pull,
                                   double height, const Eigen::Vector3d& offset)
{
  const auto mouth = [](const Json& port) {
    const Json& p = port["mouth_mm"];
    const double x = p[0].get<double>(), y = p[1].get<double>(), z = p[2].get<double>();
    return Eigen::Vector3d(x * units::mm, y * units::mm, z * units::mm);
  };
  const bool shown = shot == "shot1";
  std::vector<ReportLine> lines;
  for (const Json& sprue : fill["sprues"]) {
    const bool below = sprue.value("from", std::string("below")) == "below";
    const Eigen::Vector3d at = mouth(sprue) + offset + (below ? 0.0 : 1.5 * height) * pull;
    lines.push_back({fmt::format("{} sprue, from {}", shot, below ? "below" : "above"),
                     {at, at + (below ? -height : height) * pull},
                     {1.0F, 0.55F, 0.0F},
                     shown});
  }
  int k = 0;
  for (const Json& vent : fill["vents"]) {
    const Eigen::Vector3d at = mouth(vent) + offset + 1.5 * height * pull;
    lines.push_back({fmt::format("{} vent {}", shot, ++k), {at, at + height * pull}, {0.0F, 0.7F, 0.8F}, shown});
  }
  return lines;
}

} // namespace fibermold
