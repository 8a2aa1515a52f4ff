#include "make/runner.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <fstream>
#include <map>
#include <optional>
#include <set>

#include <fmt/format.h>
#include <spdlog/sinks/basic_file_sink.h>
#include <spdlog/sinks/stdout_sinks.h>
#include <spdlog/spdlog.h>

#include "core/atomic_file.hpp"
#include "core/input_error.hpp"
#include "core/time_left.hpp"
#include "design/design_file.hpp"
#include "design/design_view.hpp"
#include "design/did_you_mean.hpp"
#include "make/build_lock.hpp"
#include "make/content_hash.hpp"
#include "make/unset_values.hpp"

#ifndef FIBERMOLD_VERSION
#define FIBERMOLD_VERSION "unknown"
#endif

namespace fibermold {

namespace fs = std::filesystem;

namespace {

/// A stage's progress, passed on to the terminal's and written to the stage's log at each tenth of
/// the work, with the time left once it can be estimated (core/time_left.hpp).
class LoggedProgress final : public Progress {
public:
  LoggedProgress(Progress& inner, spdlog::logger& log) : inner_(inner), log_(log) {}
  void update(double fraction, std::string_view what) override
  {
    inner_.update(fraction, what);
    const std::optional<double> left = time_left_.seconds(fraction);
    if (!(fraction >= 0) || what == "done") return;
    const int tenth = static_cast<int>(std::floor(10 * std::min(fraction, 1.0)));
    if (tenth <= last_tenth_) return;
    last_tenth_ = tenth;
    log_.info("progress {:.0f} %{}: {}", 100 * std::min(fraction, 1.0),
              left ? " (~" + TimeLeft::format(*left) + " left)" : "", what);
  }
  bool interrupted() const override { return inner_.interrupted(); }

private:
  Progress& inner_;
  spdlog::logger& log_;
  TimeLeft time_left_;
  int last_tenth_ = -1;
};

std::string utc_now()
{
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buffer[32];
  std::strftime(buffer, sizeof buffer, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buffer;
}

fs::path staging_dir(const fs::path& build_dir, const std::string& stage) { return build_dir / ".staging" / stage; }

/// Every regular file under `dir`, relative to it, sorted.
std::vector<fs::path> files_under(const fs::path& dir)
{
  std::vector<fs::path> files;
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return files;
  for (const auto& entry : fs::recursive_directory_iterator(dir))
    if (entry.is_regular_file()) files.push_back(fs::relative(entry.path(), dir));
  std::sort(files.begin(), files.end());
  return files;
}

void append_make_log(const fs::path& build_dir, const std::string& line)
{
  fs::create_directories(Runner::make_log_path(build_dir).parent_path());
  std::ofstream out(Runner::make_log_path(build_dir), std::ios::app);
  out << utc_now() << " " << line << "\n";
}

/// Reasons why `now` differs from `before` for one kind of input.
void diff_maps(
    const std::map<std::string, std::string>& before, const std::map<std::string, std::string>& now,
    const std::function<std::string(const std::string& key, const std::string* was, const std::string* is)>& describe,
    std::vector<std::string>& reasons)
{
  for (const auto& [key, value] : now) {
    auto it = before.find(key);
    if (it == before.end())
      reasons.push_back(describe(key, nullptr, &value));
    else if (it->second != value)
      reasons.push_back(describe(key, &it->second, &value));
  }
  for (const auto& [key, value] : before)
    if (!now.contains(key)) reasons.push_back(describe(key, &value, nullptr));
}

std::string describe_design(const std::string& key, const std::string* was, const std::string* is)
{
  if (!was) return key + " added";
  if (!is) return key + " removed";
  if (was->size() <= 24 && is->size() <= 24) return fmt::format("{} changed ({} → {})", key, *was, *is);
  return key + " changed";
}

} // namespace

std::string StageStatus::summary(std::size_t shown) const
{
  if (reasons.size() <= shown) return fmt::format("{}", fmt::join(reasons, "; "));
  return fmt::format("{}; and {} more",
                     fmt::join(reasons.begin(), reasons.begin() + static_cast<std::ptrdiff_t>(shown), "; "),
                     reasons.size() - shown);
}

StageFailed::StageFailed(std::string stage, const std::string& why, fs::path log)
    : std::runtime_error(why), stage_(std::move(stage)), log_(std::move(log))
{
}

std::string Runner::default_program() { return std::string("fibermold ") + FIBERMOLD_VERSION; }

fs::path Runner::stamp_path(const fs::path& build_dir, const std::string& stage)
{
  return build_dir / ".stamps" / (stage + ".json");
}
fs::path Runner::log_path(const fs::path& build_dir, const std::string& stage)
{
  return build_dir / "logs" / (stage + ".log");
}
fs::path Runner::make_log_path(const fs::path& build_dir) { return build_dir / "logs" / "make.log"; }

Runner::Runner(std::vector<std::unique_ptr<Stage>> stages, std::string program) : program_(std::move(program))
{
  std::map<std::string, std::unique_ptr<Stage>> by_name;
  for (auto& s : stages) {
    const std::string name = s->name();
    if (!by_name.emplace(name, std::move(s)).second) throw std::logic_error("duplicate stage " + name);
  }
  for (const auto& [name, s] : by_name)
    for (const std::string& up : s->upstream())
      if (!by_name.contains(up)) throw std::logic_error(fmt::format("stage {} reads unknown stage {}", name, up));
  // Topological order (Kahn), ties broken by registration-independent name order.
  std::set<std::string> placed;
  while (!by_name.empty()) {
    auto ready = std::find_if(by_name.begin(), by_name.end(), [&](const auto& entry) {
      const auto ups = entry.second->upstream();
      return std::all_of(ups.begin(), ups.end(), [&](const std::string& u) { return placed.contains(u); });
    });
    if (ready == by_name.end()) throw std::logic_error("the stages' dependencies form a cycle");
    placed.insert(ready->first);
    stages_.push_back(std::move(ready->second));
    by_name.erase(ready);
  }
}

std::vector<std::string> Runner::stage_names() const
{
  std::vector<std::string> names;
  for (const auto& s : stages_) names.push_back(s->name());
  return names;
}

const Stage& Runner::stage(const std::string& name) const
{
  for (const auto& s : stages_)
    if (s->name() == name) return *s;
  throw std::logic_error("unknown stage " + name);
}

std::vector<std::string> Runner::closure(const std::vector<std::string>& targets) const
{
  const std::vector<std::string> names = stage_names();
  if (targets.empty()) return names;
  std::set<std::string> wanted;
  std::vector<std::string> todo;
  for (const std::string& t : targets) {
    if (std::find(names.begin(), names.end(), t) == names.end()) {
      std::string message = fmt::format("unknown stage '{}'", t);
      if (auto hint = closest_match(t, names)) message += fmt::format("; did you mean '{}'?", *hint);
      message += names.empty() ? "; this build has no stages" : fmt::format("; stages: {}", fmt::join(names, ", "));
      throw InputError(Diagnostic{"", 0, 0, "", message});
    }
    todo.push_back(t);
  }
  while (!todo.empty()) {
    const std::string name = todo.back();
    todo.pop_back();
    if (!wanted.insert(name).second) continue;
    for (const std::string& up : stage(name).upstream()) todo.push_back(up);
  }
  std::vector<std::string> ordered;
  for (const std::string& n : names)
    if (wanted.contains(n)) ordered.push_back(n);
  return ordered;
}

std::map<std::string, std::string> Runner::fingerprints(const Design& design) const
{
  std::map<std::string, std::string> out;
  for (const auto& stage : stages_) {
    // The design values it reads and the files they name: those of its view (design_view.hpp).
    const Design view = design_view(design, stage->design_keys_used(design));
    std::string text = fmt::format("{} {} v{}\n", program_, stage->name(), stage->version());
    for (const auto& [key, value] : view.values) text += key + " = " + value + "\n";
    for (const fs::path& file : stage->input_files(view)) text += file.string() + " " + hash_file(file) + "\n";
    for (const std::string& up : stage->upstream()) text += up + " " + out.at(up) + "\n";
    out[stage->name()] = hash_bytes(text);
  }
  return out;
}

Stamp Runner::current_inputs(const Stage& stage, const Design& design, const fs::path& build_dir) const
{
  Stamp s;
  s.program = program_;
  s.stage_version = stage.version();
  // The design values it reads and the files they name: those of its view (design_view.hpp).
  const Design view = design_view(design, stage.design_keys_used(design));
  s.design = view.values;
  for (const fs::path& file : stage.input_files(view)) s.files[file.string()] = hash_file(file);
  for (const std::string& up : stage.upstream())
    if (auto up_stamp = Stamp::load(stamp_path(build_dir, up)))
      for (const auto& [file, hash] : up_stamp->outputs) s.upstream[up + "/" + file] = hash;
  return s;
}

StageStatus Runner::stage_status(const Stage& stage, const Design& design, const fs::path& build_dir,
                                 const std::vector<StageStatus>& done) const
{
  StageStatus status{stage.name(), false, {}};
  std::vector<std::string>& reasons = status.reasons;
  const std::optional<Stamp> stamp = Stamp::load(stamp_path(build_dir, stage.name()));
  if (!stamp) {
    std::error_code ec;
    reasons.push_back(fs::exists(log_path(build_dir, stage.name()), ec) ? "last run failed or was interrupted"
                                                                        : "never built");
    return status;
  }
  for (const std::string& up : stage.upstream()) {
    auto it = std::find_if(done.begin(), done.end(), [&](const StageStatus& d) { return d.stage == up; });
    if (it != done.end() && !it->fresh) reasons.push_back(fmt::format("upstream {} is stale", up));
  }
  const Stamp now = current_inputs(stage, design, build_dir);
  if (now.program != stamp->program)
    reasons.push_back(fmt::format("program version changed ({} → {})", stamp->program, now.program));
  if (now.stage_version != stamp->stage_version)
    reasons.push_back(fmt::format("stage algorithm changed (v{} → v{})", stamp->stage_version, now.stage_version));
  diff_maps(stamp->design, now.design, describe_design, reasons);
  diff_maps(
      stamp->files, now.files,
      [&](const std::string& file, const std::string* was, const std::string* is) {
        const std::string name = fs::path(file).lexically_proximate(design.folder).string();
        if (!was) return fmt::format("file {} is a new input", name);
        if (!is) return fmt::format("file {} is no longer an input", name);
        return fmt::format("file {} changed", name);
      },
      reasons);
  if (reasons.empty() || !reasons.front().starts_with("upstream"))
    diff_maps(
        stamp->upstream, now.upstream,
        [](const std::string& file, const std::string*, const std::string*) {
          return fmt::format("upstream output {} changed", file);
        },
        reasons);
  for (const auto& [file, hash] : stamp->outputs) {
    const fs::path path = build_dir / stage.name() / file;
    std::error_code ec;
    if (!fs::exists(path, ec))
      reasons.push_back(fmt::format("output {}/{} is missing", stage.name(), file));
    else if (hash_file(path) != hash)
      reasons.push_back(fmt::format("output {}/{} was modified", stage.name(), file));
  }
  status.fresh = reasons.empty();
  return status;
}

std::vector<StageStatus> Runner::status(const Design& design, const fs::path& build_dir,
                                        const std::vector<std::string>& targets) const
{
  std::vector<StageStatus> result;
  for (const std::string& name : closure(targets))
    result.push_back(stage_status(stage(name), design, build_dir, result));
  return result;
}

std::vector<StageRun> Runner::make(const Design& design, const MakeOptions& options,
                                   const ProgressFactory& progress) const
{
  BuildLock lock(options.build_dir);
  std::vector<StageRun> runs;
  std::vector<StageStatus> done;
  for (const std::string& name : closure(options.targets)) {
    if (interrupt_requested()) throw Interrupted();
    const Stage& s = stage(name);
    StageStatus st = stage_status(s, design, options.build_dir, done);
    if (st.fresh && !options.force) {
      append_make_log(options.build_dir, name + " fresh");
      runs.push_back({name, false, 0});
    } else {
      if (!st.fresh) {
        append_make_log(options.build_dir, fmt::format("{} stale: {}", name, fmt::join(st.reasons, "; ")));
        spdlog::info("{}: running ({})", name, st.summary());
      } else
        spdlog::info("{}: running (--force)", name);
      runs.push_back(run_stage(s, design, options.build_dir, progress));
      st.fresh = true;
      st.reasons.clear();
    }
    done.push_back(st);
  }
  return runs;
}

StageRun Runner::run_stage(const Stage& stage, const Design& design, const fs::path& build_dir,
                           const ProgressFactory& progress) const
{
  const std::string name = stage.name();
  const fs::path stamp_file = stamp_path(build_dir, name);
  fs::remove(stamp_file); // from here until the new stamp, the stage is stale

  const fs::path staging = staging_dir(build_dir, name);
  fs::remove_all(staging);
  fs::create_directories(staging);
  fs::create_directories(log_path(build_dir, name).parent_path());

  auto sink = std::make_shared<spdlog::sinks::basic_file_sink_mt>(log_path(build_dir, name).string(), true);
  auto console = std::make_shared<spdlog::sinks::stderr_sink_mt>();
  console->set_level(spdlog::level::warn);
  console->set_pattern("[%n] %l: %v");
  spdlog::logger log(name, {sink, console}); // the stage's own messages; warnings reach the terminal
  log.set_level(spdlog::level::debug);
  log.flush_on(spdlog::level::info);
  spdlog::logger record(name, sink); // the runner's record of the run: the CLI reports failures itself
  record.flush_on(spdlog::level::info);
  std::unique_ptr<Progress> reporter = progress ? progress(name) : nullptr;
  NullProgress silent;
  LoggedProgress p(reporter ? *reporter : silent, record);

  const Stamp inputs = current_inputs(stage, design, build_dir);
  const auto start = std::chrono::steady_clock::now();
  const auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  record.info("{} stage v{} in {}", program_, stage.version(), build_dir.string());
  try {
    // The stage sees the keys it declares and undeclared values for the rest (design_view.hpp).
    const Design view = design_view(design, stage.design_keys_used(design));
    StageContext ctx{view, build_dir, staging, p, log};
    stage.run(ctx);
    // No output holds a value nobody computed (unset_values.hpp): a NaN in a sentence is a bug, said as one.
    const std::vector<std::string> own = own_text(design, build_dir);
    for (const fs::path& file : files_under(staging))
      if (const auto unset = unset_value_in(staging / file, own))
        throw std::runtime_error(fmt::format(
            "wrote a value it did not compute (NaN, an infinity, a JSON null or a design value it did not declare) "
            "into {}, {}. This is a bug in fibermold: please report it with the design file. None of the stage's "
            "outputs were kept",
            file.string(), *unset));
    p.update(1.0, "done");
  } catch (const std::exception& e) {
    const bool interrupted = dynamic_cast<const Interrupted*>(&e) != nullptr;
    record.error("{} after {:.2f} s: {}", interrupted ? "interrupted" : "failed", elapsed(), e.what());
    fs::remove_all(staging);
    std::error_code not_empty;
    fs::remove(staging.parent_path(), not_empty);
    append_make_log(build_dir, fmt::format("{} {} {:.3f}", name, interrupted ? "interrupted" : "failed", elapsed()));
    if (interrupted || dynamic_cast<const InputError*>(&e)) throw;
    throw StageFailed(name, e.what(), log_path(build_dir, name));
  }

  // Commit: outputs renamed into place, leftovers of the previous run removed, stamp last.
  Stamp stamp = inputs;
  const fs::path out_dir = build_dir / name;
  for (const fs::path& file : files_under(staging)) {
    stamp.outputs[file.string()] = hash_file(staging / file);
    fs::create_directories((out_dir / file).parent_path());
    fs::rename(staging / file, out_dir / file);
  }
  for (const fs::path& file : files_under(out_dir))
    if (!stamp.outputs.contains(file.string())) fs::remove(out_dir / file);
  fs::remove_all(staging);
  std::error_code not_empty; // another stage's staging: kept; none left: the folder goes too
  fs::remove(staging.parent_path(), not_empty);
  stamp.seconds = elapsed();
  stamp.finished = utc_now();
  write_file_atomic(stamp_file, stamp.to_json());
  record.info("done in {:.2f} s, {} output file(s)", stamp.seconds, stamp.outputs.size());
  append_make_log(build_dir, fmt::format("{} ran {:.3f}", name, stamp.seconds));
  return {name, true, stamp.seconds};
}

void Runner::clean(const fs::path& build_dir, const std::vector<std::string>& targets) const
{
  BuildLock lock(build_dir);
  if (!targets.empty()) closure(targets); // rejects unknown names
  for (const std::string& name : stage_names()) {
    if (!targets.empty() && std::find(targets.begin(), targets.end(), name) == targets.end()) continue;
    fs::remove(stamp_path(build_dir, name));
    fs::remove_all(build_dir / name);
    fs::remove_all(staging_dir(build_dir, name));
    fs::remove(log_path(build_dir, name));
  }
  if (targets.empty()) {
    fs::remove_all(build_dir / ".stamps");
    fs::remove_all(build_dir / ".staging");
    fs::remove_all(build_dir / "logs");
  }
}

} // namespace fibermold
