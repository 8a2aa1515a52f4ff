#include "sweep/sweep_command.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <thread>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/atomic_file.hpp"
#include "core/input_error.hpp"
#include "core/json_file.hpp"
#include "core/progress.hpp"
#include "core/shell_words.hpp"
#include "design/design_file.hpp"
#include "make/build_lock.hpp"
#include "make/content_hash.hpp"
#include "sweep/sweep_cases.hpp"
#include "sweep/sweep_plan.hpp"
#include "sweep/sweep_summary.hpp"

extern char** environ;

namespace fibermold {

namespace fs = std::filesystem;
using Json = nlohmann::json;
using Clock = std::chrono::steady_clock;

namespace {

fs::path this_program() { return fs::read_symlink("/proc/self/exe"); }

/// A command's standard output and exit status; its standard error goes to `errors` when given
/// (else to ours).
std::pair<int, std::string> capture(const std::string& command, const fs::path& errors = {})
{
  std::string out;
  FILE* pipe = popen((errors.empty() ? command : command + " 2>" + shell_quoted(errors.string())).c_str(), "r");
  if (!pipe) return {-1, out};
  char buffer[4096];
  while (fgets(buffer, sizeof buffer, pipe)) out += buffer;
  const int status = pclose(pipe);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, out};
}

/// The stages upstream of `stage`, in dependency order.
std::vector<std::string> upstream_of(const Runner& runner, const std::string& stage)
{
  std::vector<std::string> up = runner.closure({stage});
  up.pop_back();
  return up;
}

/// Each case's design, loaded once.
class Designs {
public:
  Designs(const SweepPlan& plan, fs::path build_dir) : plan_(plan), build_dir_(std::move(build_dir)) {}
  const Design& operator[](const std::string& id)
  {
    auto it = designs_.find(id);
    if (it == designs_.end())
      it = designs_.emplace(id, load_design(plan_.case_dir(build_dir_, id) / "design.toml")).first;
    return it->second;
  }

private:
  const SweepPlan& plan_;
  fs::path build_dir_;
  std::map<std::string, Design> designs_;
};

bool fresh(const Runner& runner, Designs& designs, const SweepPlan& plan, const fs::path& build_dir,
           const std::string& id, const std::string& stage)
{
  return runner.status(designs[id], plan.case_dir(build_dir, id), {stage}).back().fresh;
}

/// Brings every stage a case does not own from its owner (where the owner has built it).
void gather(const SweepPlan& plan, const fs::path& build_dir)
{
  for (const SweepCase& c : plan.cases)
    for (const std::string& stage : plan.stages)
      if (const std::string& owner = plan.owner.at(c.id).at(stage); owner != c.id)
        adopt_stage(plan.case_dir(build_dir, owner), plan.case_dir(build_dir, c.id), stage);
}

/// Per stage, the builders whose stage is stale, or downstream of one that is.
std::map<std::string, std::vector<std::string>> stale_tasks(const SweepPlan& plan, const Runner& runner,
                                                            Designs& designs, const fs::path& build_dir)
{
  std::map<std::string, std::set<std::string>> stale; // stage → builders
  std::map<std::string, std::vector<std::string>> out;
  for (const std::string& stage : plan.stages)
    for (const std::string& id : plan.builders(stage)) {
      bool run = false;
      for (const std::string& up : upstream_of(runner, stage)) {
        const std::string& owner = plan.owner.at(id).at(up);
        run = run || stale[up].contains(owner);
        if (owner != id) adopt_stage(plan.case_dir(build_dir, owner), plan.case_dir(build_dir, id), up);
      }
      if (run || !fresh(runner, designs, plan, build_dir, id, stage)) {
        stale[stage].insert(id);
        out[stage].push_back(id);
      }
    }
  return out;
}

struct TaskResult {
  std::string stage, id;
  int exit_code = 0;
  double seconds = 0;
  fs::path output;
};

fs::path task_output(const SweepPlan& plan, const fs::path& build_dir, const std::string& id, const std::string& stage)
{
  return plan.case_dir(build_dir, id) / "logs" / ("sweep-" + stage + ".txt");
}

/// The local engine: each stage's tasks as up to `jobs` child processes at once.
std::vector<TaskResult> run_local(const SweepPlan& plan, const std::map<std::string, std::vector<std::string>>& tasks,
                                  const fs::path& build_dir, int jobs)
{
  const std::string program = this_program().string();
  std::vector<TaskResult> results;
  for (const std::string& stage : plan.stages) {
    const auto it = tasks.find(stage);
    if (it == tasks.end()) continue;
    std::map<pid_t, TaskResult> running;
    std::size_t next = 0;
    fmt::print("{}: {} task(s)\n", stage, it->second.size());
    std::fflush(stdout);
    std::map<pid_t, Clock::time_point> since;
    while ((next < it->second.size() && !interrupt_requested()) || !running.empty()) {
      while (next < it->second.size() && static_cast<int>(running.size()) < jobs && !interrupt_requested()) {
        const std::string& id = it->second[next++];
        TaskResult r{stage, id, 0, 0, task_output(plan, build_dir, id, stage)};
        fs::create_directories(r.output.parent_path());
        std::vector<std::string> args{program, "sweep-task", fs::absolute(build_dir).string(), stage, id};
        std::vector<char*> argv;
        for (std::string& a : args) argv.push_back(a.data());
        argv.push_back(nullptr);
        posix_spawn_file_actions_t actions;
        posix_spawn_file_actions_init(&actions);
        posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, r.output.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
        pid_t pid = 0;
        const int failed = posix_spawn(&pid, program.c_str(), &actions, nullptr, argv.data(), environ);
        posix_spawn_file_actions_destroy(&actions);
        if (failed) {
          for (const auto& [child, task] : running) ::waitpid(child, nullptr, 0);
          throw std::runtime_error(fmt::format("cannot start {}: {}", program, std::strerror(failed)));
        }
        running[pid] = r;
        since[pid] = Clock::now();
      }
      int status = 0;
      const pid_t done = waitpid(-1, &status, 0);
      if (done < 0) {
        // Ctrl-C reaches the children too (one process group); a SIGTERM to this process alone is
        // passed on to them. Either way each stops at its next checkpoint.
        if (errno == EINTR && interrupt_requested())
          for (const auto& [child, task] : running) ::kill(child, SIGTERM);
        if (errno == EINTR) continue;
        break;
      }
      auto found = running.find(done);
      if (found == running.end()) continue;
      TaskResult r = found->second;
      running.erase(found);
      r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
      r.seconds = std::chrono::duration<double>(Clock::now() - since[done]).count();
      fmt::print("  case {} {}: {} in {:.1f} s\n", r.id, stage,
                 r.exit_code == 0 ? "done" : fmt::format("FAILED (exit {})", r.exit_code), r.seconds);
      std::fflush(stdout);
      results.push_back(r);
    }
    if (interrupt_requested()) throw Interrupted();
  }
  return results;
}

SlurmOptions merged(SlurmOptions file, const SlurmOptions& cli)
{
  for (const auto& [option, value] : {std::pair{"--partition", cli.partition}, std::pair{"--time", cli.time}})
    if (!is_slurm_word(value))
      throw InputError(Diagnostic{{}, 0, 0, option, fmt::format("\"{}\" is not a Slurm value", value)});
  if (!cli.partition.empty()) file.partition = cli.partition;
  if (!cli.time.empty()) file.time = cli.time;
  if (cli.cpus_per_task > 0) file.cpus_per_task = cli.cpus_per_task;
  file.extra.insert(file.extra.end(), cli.extra.begin(), cli.extra.end());
  return file;
}

/// The Slurm engine: one job array per stage, each after the one before (afterany: a failed case
/// does not hold up the others; its downstream tasks see it and fail at once). Each submission is
/// recorded in slurm/jobs.json as soon as it is made. Returns stage → job id.
std::map<std::string, std::string> submit_slurm(const SweepPlan& plan,
                                                const std::map<std::string, std::vector<std::string>>& tasks,
                                                const fs::path& build_dir, const SlurmOptions& o)
{
  const fs::path dir = fs::absolute(build_dir) / "slurm";
  fs::create_directories(dir);
  std::map<std::string, std::string> jobs;
  Json recorded = Json::object();
  std::string previous;
  for (const std::string& stage : plan.stages) {
    const auto it = tasks.find(stage);
    if (it == tasks.end()) continue;
    // The cases are in the script itself: a later sweep rewrites the files, not a queued task's list.
    std::string script = "#!/bin/sh\n";
    script += fmt::format("#SBATCH --job-name=fibermold-{}-{}\n", plan.name, stage);
    script += fmt::format("#SBATCH --array=0-{}\n", it->second.size() - 1);
    script += fmt::format("#SBATCH --output={}\n", (dir / (stage + "-%a.out")).string());
    if (!o.partition.empty()) script += "#SBATCH --partition=" + o.partition + "\n";
    if (!o.time.empty()) script += "#SBATCH --time=" + o.time + "\n";
    if (o.cpus_per_task > 0) script += fmt::format("#SBATCH --cpus-per-task={}\n", o.cpus_per_task);
    script += fmt::format("set -- {}\nshift \"$SLURM_ARRAY_TASK_ID\"\n", fmt::join(it->second, " "));
    script += fmt::format("exec {} sweep-task {} {} \"$1\"\n", shell_quoted(this_program().string()),
                          shell_quoted(fs::absolute(build_dir).string()), stage);
    const fs::path file = dir / fmt::format("{}-{}.sh", stage, hash_bytes(script).substr(0, 8));
    write_file_atomic(file, script);
    std::string command = "sbatch --parsable";
    if (!previous.empty()) command += " --dependency=afterany:" + previous;
    for (const std::string& flag : o.extra) command.append(" ").append(shell_quoted(flag));
    command.append(" ").append(shell_quoted(file.string()));
    const auto [code, out] = capture(command, dir / "sbatch.err");
    if (code != 0 || out.empty())
      throw std::runtime_error(
          fmt::format("sbatch failed for stage {} (exit {}): {}", stage, code, read_file(dir / "sbatch.err")));
    previous = out.substr(0, out.find_first_of(";\n"));
    jobs[stage] = previous;
    recorded[stage] = {{"job", previous}, {"tasks", it->second}};
    write_json_atomic(dir / "jobs.json", recorded);
    fmt::print("{}: {} task(s), Slurm job {}\n", stage, it->second.size(), previous);
    std::fflush(stdout);
  }
  return jobs;
}

/// Queue states of the sweep's array tasks ("<job>_<index>" → "PENDING"); throws when squeue fails.
std::map<std::string, std::string> queued(const std::map<std::string, std::string>& jobs, const fs::path& build_dir)
{
  std::map<std::string, std::string> out;
  if (jobs.empty()) return out;
  std::string ids;
  for (const auto& [stage, id] : jobs) ids += (ids.empty() ? "" : ",") + id;
  const fs::path errors = fs::absolute(build_dir) / "slurm" / "squeue.err";
  const auto [code, text] = capture("squeue -h -r -o '%i %T' -j " + ids, errors);
  if (code != 0) {
    const std::string why = read_file(errors);
    if (why.find("Invalid job id") != std::string::npos) return out; // long finished and purged
    throw std::runtime_error("squeue failed: " + why);
  }
  std::istringstream lines(text);
  for (std::string task, state; lines >> task >> state;) out[task] = state;
  return out;
}

std::map<std::string, std::string> recorded_jobs(const fs::path& build_dir,
                                                 std::map<std::string, std::vector<std::string>>* tasks)
{
  std::map<std::string, std::string> jobs;
  const fs::path file = build_dir / "slurm" / "jobs.json";
  std::error_code ec;
  if (!fs::exists(file, ec)) return jobs;
  const Json recorded = Json::parse(read_file(file));
  for (const auto& [stage, j] : recorded.items()) {
    jobs[stage] = j["job"].get<std::string>();
    if (tasks) (*tasks)[stage] = j["tasks"].get<std::vector<std::string>>();
  }
  return jobs;
}

/// Per stage: how many builders are built, and the failed ones with their logs.
int report(const SweepPlan& plan, const Runner& runner, Designs& designs, const fs::path& build_dir,
           const std::map<std::string, std::string>& queue_states, const std::map<std::string, std::string>& jobs,
           const std::map<std::string, std::vector<std::string>>& job_tasks)
{
  int failed = 0, waiting = 0;
  for (const std::string& stage : plan.stages) {
    const std::vector<std::string> builders = plan.builders(stage);
    std::vector<std::string> problems;
    int built = 0;
    for (const std::string& id : builders) {
      if (fresh(runner, designs, plan, build_dir, id, stage)) {
        ++built;
        continue;
      }
      // Where a Slurm task of this build wrote its output, and its state if it is still queued.
      fs::path out = task_output(plan, build_dir, id, stage);
      std::string state;
      if (const auto job = jobs.find(stage); job != jobs.end() && job_tasks.contains(stage)) {
        const auto& list = job_tasks.at(stage);
        if (const auto at = std::find(list.begin(), list.end(), id); at != list.end()) {
          out = build_dir / "slurm" / fmt::format("{}-{}.out", stage, at - list.begin());
          if (auto q = queue_states.find(fmt::format("{}_{}", job->second, at - list.begin())); q != queue_states.end())
            state = q->second;
        }
      }
      if (!state.empty()) {
        ++waiting;
        problems.push_back(fmt::format("case {}: {}", id, state));
        continue;
      }
      ++failed;
      const fs::path log = Runner::log_path(plan.case_dir(build_dir, id), stage);
      std::error_code ec;
      problems.push_back(fmt::format("case {}: failed or not run; log {}{}", id,
                                     fs::exists(log, ec) ? log.string() : "(none)",
                                     fs::exists(out, ec) ? ", task output " + out.string() : ""));
    }
    fmt::print("  {:<9} {} of {} built{}\n", stage, built, builders.size(), problems.empty() ? "" : ":");
    for (const std::string& p : problems) fmt::print("    {}\n", p);
  }
  if (waiting > 0) fmt::print("{} task(s) still queued or running\n", waiting);
  return failed > 0 ? 1 : 0;
}

void print_sharing(const SweepPlan& plan)
{
  std::string shares;
  for (const std::string& stage : plan.stages)
    shares += fmt::format("{}{} {}", shares.empty() ? "" : ", ", stage, plan.builders(stage).size());
  fmt::print("sweep {}: {} case(s); distinct builds per stage: {}\n", plan.name, plan.cases.size(), shares);
}

} // namespace

int run_sweep(const SweepRequest& request, const Runner& runner)
{
  const SweepFile sweep = load_sweep(request.sweep);
  const fs::path build_dir = request.build_dir.empty() ? fs::path("out") / ("sweep-" + sweep.name) : request.build_dir;
  if (request.engine != "local" && request.engine != "slurm")
    throw InputError(
        Diagnostic{{}, 0, 0, "--engine", fmt::format("'{}' is not an engine: local or slurm", request.engine)});

  if (request.status) {
    const SweepPlan plan = read_plan(build_dir);
    Designs designs(plan, build_dir);
    std::map<std::string, std::vector<std::string>> job_tasks;
    const auto jobs = recorded_jobs(build_dir, &job_tasks);
    const auto states = queued(jobs, build_dir);
    print_sharing(plan);
    const int code = report(plan, runner, designs, build_dir, states, jobs, job_tasks);
    // Once the queue is empty, the summary (after gathering every case's stages), unless a sweep
    // is running here.
    if (states.empty()) try {
        const BuildLock lock(build_dir);
        gather(plan, build_dir);
        write_sweep_summary(plan, build_dir);
        fmt::print("summary: {}\n", (build_dir / "summary.csv").string());
      } catch (const BuildLocked&) {
        fmt::print("a sweep is running in {}: no summary yet\n", build_dir.string());
      }
    return code;
  }

  const auto started = Clock::now();
  const std::vector<SweepCase> cases = expand_sweep(sweep);
  fs::create_directories(build_dir);
  const BuildLock lock(build_dir);
  // A sweep whose Slurm jobs are still queued is not planned again: its tasks read the plan.
  {
    const auto recorded = recorded_jobs(build_dir, nullptr);
    if (!recorded.empty() && std::system("command -v squeue >/dev/null 2>&1") == 0 &&
        !queued(recorded, build_dir).empty())
      throw std::runtime_error(fmt::format(
          "the Slurm jobs of the last run of this sweep are still queued or running; see `fibermold sweep {} "
          "--status`, or scancel them first",
          request.sweep.string()));
  }
  const SweepPlan plan = plan_sweep(sweep, cases, runner, build_dir);
  write_plan(plan, build_dir);
  print_sharing(plan);
  Designs designs(plan, build_dir);
  const auto tasks = stale_tasks(plan, runner, designs, build_dir);
  if (tasks.empty()) fmt::print("every case is up to date\n");

  if (request.engine == "slurm") {
    const auto jobs = submit_slurm(plan, tasks, build_dir, merged(sweep.slurm, request.slurm));
    if (!request.wait) {
      fmt::print("submitted; `fibermold sweep {} --status{}` reports progress\n", request.sweep.string(),
                 request.build_dir.empty() ? "" : " --build-dir " + request.build_dir.string());
      return 0;
    }
    // Polling squeue: every second at first, then less often (a cluster's controller is shared).
    // Slept in tenths of a second, so that Ctrl-C is answered within one.
    for (int wait = 1; !queued(jobs, build_dir).empty(); wait = std::min(2 * wait, 5)) {
      for (int tenth = 0; tenth < 10 * wait && !interrupt_requested(); ++tenth)
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
      if (interrupt_requested()) {
        fmt::print(stderr, "fibermold: stopped waiting; the jobs stay queued (`fibermold sweep {} --status`)\n",
                   request.sweep.string());
        return 130;
      }
    }
  } else {
    fs::remove(build_dir / "slurm" / "jobs.json"); // the last run's jobs are history now
    const int jobs =
        request.jobs > 0 ? request.jobs : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    run_local(plan, tasks, build_dir, jobs);
  }
  gather(plan, build_dir);
  write_sweep_summary(plan, build_dir);
  Designs fresh_designs(plan, build_dir);
  std::map<std::string, std::vector<std::string>> job_tasks;
  const auto jobs =
      request.engine == "slurm" ? recorded_jobs(build_dir, &job_tasks) : std::map<std::string, std::string>{};
  fmt::print("sweep done in {:.1f} s:\n", std::chrono::duration<double>(Clock::now() - started).count());
  const int code = report(plan, runner, fresh_designs, build_dir, {}, jobs, job_tasks);
  fmt::print("summary: {} and summary.html\n", (build_dir / "summary.csv").string());
  return code;
}

int run_sweep_task(const fs::path& build_dir, const std::string& stage, const std::string& case_id,
                   const Runner& runner)
{
  const SweepPlan plan = read_plan(build_dir);
  if (!plan.owner.contains(case_id))
    throw std::runtime_error(fmt::format("no case {} in {}", case_id, (build_dir / "sweep.json").string()));
  Designs designs(plan, build_dir);
  const fs::path dir = plan.case_dir(build_dir, case_id);
  // Every upstream stage must be built already, by its own task: a task never builds another's stage.
  for (const std::string& up : upstream_of(runner, stage)) {
    const std::string& owner = plan.owner.at(case_id).at(up);
    if (!fresh(runner, designs, plan, build_dir, owner, up)) {
      fmt::print(stderr,
                 "sweep: case {} needs stage {}{}, which is not built: its task failed or did not run (log: {})\n",
                 case_id, up, owner == case_id ? "" : " from case " + owner,
                 Runner::log_path(plan.case_dir(build_dir, owner), up).string());
      return 1;
    }
    if (owner != case_id) adopt_stage(plan.case_dir(build_dir, owner), dir, up);
  }
  const auto runs = runner.make(designs[case_id], {dir, {stage}, false});
  for (const StageRun& r : runs)
    if (r.ran) fmt::print("case {} {}: done in {:.2f} s\n", case_id, r.stage, r.seconds);
  return 0;
}

} // namespace fibermold
