#include "make/stamp.hpp"

#include <nlohmann/json.hpp>

#include "core/atomic_file.hpp"
#include "core/json_file.hpp"

namespace fibermold {

std::string Stamp::to_json() const
{
  nlohmann::ordered_json j;
  j["program"] = program;
  j["stage_version"] = stage_version;
  j["design"] = design;
  j["files"] = files;
  j["upstream"] = upstream;
  j["outputs"] = outputs;
  j["seconds"] = seconds;
  j["finished"] = finished;
  return checked_json(j, "stamp.json");
}

std::optional<Stamp> Stamp::load(const std::filesystem::path& path)
{
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return std::nullopt;
  try {
    const nlohmann::json j = nlohmann::json::parse(read_file(path));
    Stamp s;
    s.program = j.at("program").get<std::string>();
    s.stage_version = j.at("stage_version").get<int>();
    s.design = j.at("design").get<std::map<std::string, std::string>>();
    s.files = j.at("files").get<std::map<std::string, std::string>>();
    s.upstream = j.at("upstream").get<std::map<std::string, std::string>>();
    s.outputs = j.at("outputs").get<std::map<std::string, std::string>>();
    s.seconds = j.at("seconds").get<double>();
    s.finished = j.at("finished").get<std::string>();
    return s;
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

} // namespace fibermold
