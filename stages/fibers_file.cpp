#include "stages/fibers_file.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/atomic_file.hpp"
#include "core/json_file.hpp"
#include "core/units.hpp"
#include "sim/hermite_spline.hpp"

namespace fibermold {

namespace {
using Json = nlohmann::ordered_json;

Json to_mm(const std::vector<Eigen::Vector3d>& v)
{
  Json out = Json::array();
  for (const Eigen::Vector3d& p : v) out.push_back({p.x() / units::mm, p.y() / units::mm, p.z() / units::mm});
  return out;
}

std::vector<Eigen::Vector3d> from_mm(const Json& j)
{
  std::vector<Eigen::Vector3d> out;
  for (const Json& p : j)
    out.emplace_back(p.at(0).get<double>() * units::mm, p.at(1).get<double>() * units::mm,
                     p.at(2).get<double>() * units::mm);
  return out;
}
} // namespace

std::string fibers_json(const FibersFile& f)
{
  Json fibers = Json::array();
  for (std::size_t k = 0; k < f.routing.routes.size(); ++k) {
    const Route& r = f.routing.routes[k];
    Json pressures = Json::object();
    for (std::size_t t = 0; t < f.targets.size(); ++t)
      pressures[f.targets[t]] =
          f.routing.pressures(static_cast<Eigen::Index>(t), static_cast<Eigen::Index>(k)) / units::kPa;
    fibers.push_back({{"name", r.name},
                      {"points_mm", to_mm(r.points)},
                      {"tangents_mm", to_mm(r.tangents)},
                      {"length_mm", HermiteSpline(r.points, r.tangents).length() / units::mm},
                      {"pressure_kPa", pressures}});
  }
  return checked_json(Json{{"optimized", f.optimized}, {"fibers", fibers}}, "fibers.json");
}

FibersFile read_fibers_json(const std::filesystem::path& path)
{
  try {
    const Json j = Json::parse(read_file(path));
    FibersFile f;
    f.optimized = j.at("optimized").get<bool>();
    const Json& fibers = j.at("fibers");
    for (const Json& fb : fibers)
      f.routing.routes.push_back(
          {fb.at("name").get<std::string>(), from_mm(fb.at("points_mm")), from_mm(fb.at("tangents_mm"))});
    if (!fibers.empty())
      for (const auto& [name, value] : fibers.front().at("pressure_kPa").items()) f.targets.push_back(name);
    f.routing.pressures.resize(static_cast<Eigen::Index>(f.targets.size()), static_cast<Eigen::Index>(fibers.size()));
    for (std::size_t k = 0; k < fibers.size(); ++k)
      for (std::size_t t = 0; t < f.targets.size(); ++t)
        f.routing.pressures(static_cast<Eigen::Index>(t), static_cast<Eigen::Index>(k)) =
            fibers[k].at("pressure_kPa").at(f.targets[t]).get<double>() * units::kPa;
    return f;
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(fmt::format("{}: not a fibers file: {}", path.string(), e.what()));
  }
}

} // namespace fibermold
