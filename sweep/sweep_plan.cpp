#include "sweep/sweep_plan.hpp"

#include <fstream>

#include <nlohmann/json.hpp>

#include "core/atomic_file.hpp"
#include "core/json_file.hpp"
#include "design/design_file.hpp"

namespace fibermold {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

std::vector<std::string> SweepPlan::builders(const std::string& stage) const
{
  std::vector<std::string> out;
  for (const SweepCase& c : cases)
    if (owner.at(c.id).at(stage) == c.id) out.push_back(c.id);
  return out;
}

SweepPlan plan_sweep(const SweepFile& sweep, const std::vector<SweepCase>& cases, const Runner& runner,
                     const fs::path& build_dir)
{
  SweepPlan plan{sweep.file, sweep.name, sweep.axes, cases, runner.stage_names(), {}};
  // The last plan's owners keep their builds: a case added in front of the others adopts them
  // instead of building them again.
  std::map<std::string, std::map<std::string, std::string>> owned_before;
  try {
    owned_before = read_plan(build_dir).owner;
  } catch (const std::exception&) {
  }
  std::map<std::string, std::map<std::string, std::vector<std::string>>> groups; // stage → fingerprint → cases
  for (const SweepCase& c : cases) {
    const fs::path design_file = plan.case_dir(build_dir, c.id) / "design.toml";
    fs::create_directories(design_file.parent_path());
    std::error_code ec;
    if (!fs::exists(design_file, ec) || read_file(design_file) != c.design) write_file_atomic(design_file, c.design);
    const std::map<std::string, std::string> prints = runner.fingerprints(load_design(design_file));
    for (const std::string& stage : plan.stages) groups[stage][prints.at(stage)].push_back(c.id);
  }
  for (const auto& [stage, by_print] : groups)
    for (const auto& [print, members] : by_print) {
      std::string owner = members.front();
      for (const std::string& id : members)
        if (auto it = owned_before.find(id);
            it != owned_before.end() && it->second.contains(stage) && it->second.at(stage) == id) {
          owner = id;
          break;
        }
      for (const std::string& id : members) plan.owner[id][stage] = owner;
    }
  return plan;
}

void write_plan(const SweepPlan& plan, const fs::path& build_dir)
{
  Json cases = Json::array();
  for (const SweepCase& c : plan.cases)
    cases.push_back({{"id", c.id}, {"values", c.values}, {"owner", plan.owner.at(c.id)}});
  const Json j{{"sweep", plan.sweep_file.string()},
               {"name", plan.name},
               {"axes", plan.axes},
               {"stages", plan.stages},
               {"cases", cases}};
  write_json_atomic(build_dir / "sweep.json", j);
}

SweepPlan read_plan(const fs::path& build_dir)
{
  const fs::path file = build_dir / "sweep.json";
  try {
    const Json j = Json::parse(read_file(file));
    SweepPlan plan;
    plan.sweep_file = j.at("sweep").get<std::string>();
    plan.name = j.at("name").get<std::string>();
    plan.axes = j.at("axes").get<std::vector<std::string>>();
    plan.stages = j.at("stages").get<std::vector<std::string>>();
    for (const Json& c : j.at("cases")) {
      plan.cases.push_back({c.at("id").get<std::string>(), c.at("values").get<std::vector<std::string>>(), {}});
      plan.owner[plan.cases.back().id] = c.at("owner").get<std::map<std::string, std::string>>();
    }
    return plan;
  } catch (const std::exception& e) {
    throw std::runtime_error(file.string() + ": not a sweep plan fibermold can read (" + e.what() +
                             "); run the sweep again");
  }
}

void adopt_stage(const fs::path& from, const fs::path& to, const std::string& stage)
{
  const fs::path stamp = Runner::stamp_path(from, stage), their_stamp = Runner::stamp_path(to, stage);
  const fs::path log = Runner::log_path(from, stage), their_log = Runner::log_path(to, stage);
  std::error_code ec;
  if (!fs::exists(stamp, ec)) return; // nothing to adopt: what `to` has stays, and the runner judges it
  if (fs::exists(their_stamp, ec) && fs::equivalent(stamp, their_stamp, ec)) return; // this very build already
  fs::remove(their_stamp);
  fs::remove_all(to / stage);
  fs::remove(their_log);
  const auto link = [](const fs::path& a, const fs::path& b) {
    fs::create_directories(b.parent_path());
    std::error_code failed;
    fs::create_hard_link(a, b, failed);
    if (failed) fs::copy_file(a, b, fs::copy_options::overwrite_existing);
  };
  if (fs::is_directory(from / stage, ec))
    for (const fs::directory_entry& e : fs::recursive_directory_iterator(from / stage))
      if (e.is_regular_file()) link(e.path(), to / stage / e.path().lexically_relative(from / stage));
  // The log is copied: the runner rewrites a log in place when it runs the stage.
  if (fs::exists(log, ec)) {
    fs::create_directories(their_log.parent_path());
    fs::copy_file(log, their_log, fs::copy_options::overwrite_existing);
  }
  link(stamp, their_stamp); // last: until here the stage is stale in `to`
}

} // namespace fibermold
