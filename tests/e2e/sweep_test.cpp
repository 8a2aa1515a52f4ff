// `fibermold sweep` as a lab runs it: six cases over [mold] wall and one optimization setting
// optimize twice, not six times; a failed case is reported and the others go on; and the same
// sweep on a throwaway single-node Slurm cluster (Debian's slurm-wlm and munge, started here)
// gives the local run's results bit for bit, and a task killed with scancel is reported and is all
// that a rerun builds.
#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <thread>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "test_support.hpp"

namespace fibermold {
namespace {

using ::testing::HasSubstr;
namespace fs = std::filesystem;

const std::string kDesign = std::string(test::kBarDesign) + test::kBarMuscle + test::kBarTrackingCurve +
                            test::kBarTarget + "[mold]\nvoxel = 0.4\n";

const char* kSweep = R"([sweep]
design = "design.toml"
name = "walls"
[axes]
"mold.wall" = [3, 4, 5]
"optimize.max_iterations" = [3, 5]
)";

class SweepE2E : public ::testing::Test {
protected:
  void SetUp() override
  {
    test::write_bar(dir_.path());
    test::write_text(dir_ / "design.toml", kDesign);
    test::write_text(dir_ / "sweep.toml", kSweep);
  }
  test::CommandResult sweep(const std::string& options, const std::string& env = {})
  {
    return test::run_fibermold("sweep sweep.toml " + options, dir_.path(), env);
  }
  /// The cases of a sweep folder.
  static std::vector<fs::path> cases(const fs::path& build)
  {
    std::vector<fs::path> out;
    for (const auto& e : fs::directory_iterator(build / "cases")) out.push_back(e.path());
    std::sort(out.begin(), out.end());
    return out;
  }
  /// How many distinct files (inodes) the cases' copies of `file` are.
  static std::size_t distinct(const fs::path& build, const std::string& file)
  {
    std::set<ino_t> inodes;
    for (const fs::path& c : cases(build)) {
      struct stat s {};
      if (::stat((c / file).c_str(), &s) == 0) inodes.insert(s.st_ino);
    }
    return inodes.size();
  }

  test::TempDir dir_;
};

TEST_F(SweepE2E, SixCasesOptimizeOncePerDistinctOptimizationInput)
{
  const auto r = sweep("--jobs 3 --build-dir local");
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_THAT(
      r.out,
      HasSubstr("6 case(s); distinct builds per stage: mesh 1, targets 1, optimize 2, collide 2, molds 6, export 6"));
  EXPECT_THAT(r.out, HasSubstr("optimize: 2 task(s)"));
  const fs::path build = dir_ / "local";
  ASSERT_EQ(cases(build).size(), 6u);
  // Two optimizations ran; every case holds one of their two outputs, shared by hard links.
  EXPECT_EQ(distinct(build, "optimize/fibers.json"), 2u);
  EXPECT_EQ(distinct(build, "molds/shot1-upper.stl"), 6u);
  for (const fs::path& c : cases(build)) EXPECT_TRUE(fs::exists(c / "export" / "manifest.json")) << c;

  const std::string csv = test::read_text(build / "summary.csv");
  std::istringstream lines(csv);
  std::string header, line;
  std::getline(lines, header);
  EXPECT_THAT(header, HasSubstr("case,mold.wall,optimize.max_iterations,s RMSE mm,s max mm,s turn RMS deg,m1 s kPa,"
                                "optimizer,silicone mL,mold parts,"));
  EXPECT_TRUE(header.ends_with(",report,best for")) << header;
  int rows = 0, best = 0;
  while (std::getline(lines, line)) {
    ++rows;
    best += line.ends_with(",s") ? 1 : 0;
    // How each optimization ended, and the case's own report beside it.
    EXPECT_THAT(line, ::testing::ContainsRegex(
                          ",(gradient tolerance met|converged|stalled|line search failed|iteration limit),"));
    EXPECT_THAT(line, ::testing::ContainsRegex(",cases/[0-9a-f]{10}/export/report.html,"));
  }
  EXPECT_EQ(rows, 6);
  // The three walls of the better optimization share its routes and its RMSE: each is best.
  EXPECT_EQ(best, 3);
  const std::string html = test::read_text(build / "summary.html");
  EXPECT_THAT(html, HasSubstr("<svg"));
  EXPECT_THAT(html, ::testing::ContainsRegex("<a href=\"cases/[0-9a-f]{10}/export/report.html\">report.html</a>"));

  // Nothing is stale: nothing runs. A new wall, put first, builds molds and export for its two
  // cases only: the optimizations stay with the cases that built them.
  EXPECT_THAT(sweep("--build-dir local").out, HasSubstr("every case is up to date"));
  test::write_text(dir_ / "sweep.toml",
                   std::string(kSweep).replace(std::string(kSweep).find("[3, 4, 5]"), 9, "[2, 3, 4, 5]"));
  const auto edited = sweep("--build-dir local");
  ASSERT_EQ(edited.exit_code, 0) << edited.out << edited.err;
  EXPECT_THAT(edited.out, ::testing::Not(HasSubstr("optimize:")));
  EXPECT_THAT(edited.out, HasSubstr("molds: 2 task(s)"));
}

TEST_F(SweepE2E, FailedCaseIsReportedAndTheOthersGoOn)
{
  test::write_text(dir_ / "sweep.toml", "[sweep]\ndesign = \"design.toml\"\n[axes]\n\"optimize.enabled\" = [false]\n"
                                        "\"export.printer_volume\" = [[250, 210, 210], [40, 40, 40]]\n");
  const auto r = sweep("--build-dir out");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.out, HasSubstr("molds     1 of 2 built:"));
  EXPECT_THAT(r.out, ::testing::ContainsRegex("case [0-9a-f]{10}: failed or not run; log .*/logs/molds.log"));
  int exported = 0;
  for (const fs::path& c : cases(dir_ / "out")) exported += fs::exists(c / "export" / "manifest.json") ? 1 : 0;
  EXPECT_EQ(exported, 1);
  const auto again = sweep("--build-dir out");
  EXPECT_EQ(again.exit_code, 1);
  EXPECT_THAT(again.out, HasSubstr("molds: 1 task(s)")); // the failed case only
  EXPECT_THAT(again.out, ::testing::Not(HasSubstr("mesh:")));
}

/// A single-node Slurm cluster of our own: munged, slurmctld and slurmd in a temporary folder,
/// on ports of our own, stopped by their PIDs.
class SlurmCluster {
public:
  SlurmCluster()
  {
    for (const char* tool : {"munged", "mungekey", "slurmctld", "slurmd", "sbatch", "squeue", "scancel"})
      if (std::system(("command -v " + std::string(tool) + " >/dev/null 2>&1 || test -x /usr/sbin/" + tool).c_str()) !=
          0) {
        why_not_ = std::string(tool) + " is not installed (scripts/setup installs slurm-wlm and munge)";
        return;
      }
    const fs::path d = dir_.path();
    for (const char* sub : {"state", "spool", "munge"}) fs::create_directories(d / sub);
    char host[256] = {};
    ::gethostname(host, sizeof host - 1);
    std::string shortname(host);
    shortname = shortname.substr(0, shortname.find('.'));
    const int port = 20000 + static_cast<int>(::getpid() % 20000) * 2;
    const std::string socket = (d / "munge" / "munge.socket").string();
    test::write_text(
        d / "slurm.conf",
        "ClusterName=fibermoldtest\nSlurmctldHost=" + shortname + "\nSlurmctldPort=" + std::to_string(port) +
            "\nSlurmdPort=" + std::to_string(port + 1) + "\nAuthType=auth/munge\nAuthInfo=socket=" + socket +
            "\nCredType=cred/munge\nStateSaveLocation=" + (d / "state").string() +
            "\nSlurmdSpoolDir=" + (d / "spool").string() + "\nSlurmctldPidFile=" + (d / "slurmctld.pid").string() +
            "\nSlurmdPidFile=" + (d / "slurmd.pid").string() +
            "\nProctrackType=proctrack/linuxproc\nTaskPlugin=task/none\nSelectType=select/cons_tres\n"
            "SelectTypeParameters=CR_Core\nSchedulerParameters=batch_sched_delay=0,sched_min_interval=0\n"
            "SlurmUser=root\nSlurmdUser=root\nReturnToService=2\nMpiDefault=none\nJobCompType=jobcomp/none\n"
            "AccountingStorageType=accounting_storage/none\nSlurmctldLogFile=" +
            (d / "slurmctld.log").string() + "\nSlurmdLogFile=" + (d / "slurmd.log").string() +
            "\nNodeName=" + shortname + " CPUs=2 State=UNKNOWN\nPartitionName=debug Nodes=" + shortname +
            " Default=YES MaxTime=INFINITE State=UP\n");
    env_ = "SLURM_CONF='" + (d / "slurm.conf").string() + "'";
    const std::string key = (d / "munge" / "munge.key").string();
    if (std::system(("mungekey -c -k '" + key + "' >/dev/null 2>&1").c_str()) != 0) {
      why_not_ = "mungekey could not create a key";
      return;
    }
    munged_ = start({"munged", "-F", "-f", "--key-file=" + key, "--socket=" + socket,
                     "--pid-file=" + (d / "munge" / "pid").string(), "--log-file=" + (d / "munge" / "log").string(),
                     "--seed-file=" + (d / "munge" / "seed").string()},
                    d / "munged.out");
    if (!wait_for([&] { return fs::exists(socket); })) {
      why_not_ = "munged did not start: " + test::read_text(d / "munged.out");
      return;
    }
    slurmctld_ = start({"slurmctld", "-D", "-i"}, d / "slurmctld.out");
    slurmd_ = start({"slurmd", "-D"}, d / "slurmd.out");
    if (!wait_for([&] { return run("sinfo -h -o %T").find("idle") != std::string::npos; })) {
      why_not_ =
          "the Slurm daemons did not start; " + (d / "slurmctld.log").string() + ": " + tail(d / "slurmctld.log");
      return;
    }
  }
  ~SlurmCluster()
  {
    for (pid_t pid : {slurmd_, slurmctld_, munged_})
      if (pid > 0) {
        ::kill(pid, SIGTERM);
        ::waitpid(pid, nullptr, 0);
      }
  }
  const std::string& why_not() const { return why_not_; }
  const std::string& env() const { return env_; }
  /// A command's output under this cluster's configuration.
  std::string run(const std::string& command) const
  {
    std::string out;
    FILE* pipe = ::popen((env_ + " " + command + " 2>&1").c_str(), "r");
    if (!pipe) return out;
    char buffer[1024];
    while (fgets(buffer, sizeof buffer, pipe)) out += buffer;
    ::pclose(pipe);
    return out;
  }

private:
  pid_t start(const std::vector<std::string>& args, const fs::path& output)
  {
    const pid_t pid = ::fork();
    if (pid == 0) {
      ::setsid();
      ::setenv("SLURM_CONF", (dir_.path() / "slurm.conf").c_str(), 1);
      const int fd = ::open(output.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      ::dup2(fd, 1);
      ::dup2(fd, 2);
      std::vector<char*> argv;
      std::vector<std::string> copy = args;
      for (std::string& a : copy) argv.push_back(a.data());
      argv.push_back(nullptr);
      ::execvp(argv[0], argv.data());
      std::string sbin = "/usr/sbin/" + args[0];
      ::execv(sbin.c_str(), argv.data());
      ::_exit(127);
    }
    return pid;
  }
  template <class Ready> static bool wait_for(Ready ready)
  {
    for (int i = 0; i < 100; ++i, std::this_thread::sleep_for(std::chrono::milliseconds(100)))
      if (ready()) return true;
    return false;
  }
  static std::string tail(const fs::path& file)
  {
    std::error_code ec;
    if (!fs::exists(file, ec)) return "(no log)";
    const std::string text = test::read_text(file);
    return text.substr(text.size() > 600 ? text.size() - 600 : 0);
  }

  test::TempDir dir_;
  std::string why_not_, env_;
  pid_t munged_ = -1, slurmctld_ = -1, slurmd_ = -1;
};

TEST_F(SweepE2E, SlurmJobArraysGiveTheLocalResultsAndAKilledTaskIsAllARerunBuilds)
{
  SlurmCluster slurm;
  if (!slurm.why_not().empty()) GTEST_SKIP() << slurm.why_not();

  const auto local = sweep("--jobs 2 --build-dir local");
  ASSERT_EQ(local.exit_code, 0) << local.out << local.err;
  const auto cluster = sweep("--engine slurm --build-dir slurm --time 00:10:00 --cpus-per-task 1", slurm.env());
  ASSERT_EQ(cluster.exit_code, 0) << cluster.out << cluster.err;
  int scripts = 0;
  for (const auto& e : fs::directory_iterator(dir_ / "slurm" / "slurm"))
    if (e.path().extension() == ".sh") {
      ++scripts;
      EXPECT_THAT(test::read_text(e.path()), HasSubstr("#SBATCH --time=00:10:00\n#SBATCH --cpus-per-task=1\n"))
          << e.path();
    }
  EXPECT_EQ(scripts, 6);
  EXPECT_THAT(cluster.out, HasSubstr("optimize: 2 task(s), Slurm job"));
  EXPECT_EQ(distinct(dir_ / "slurm", "optimize/fibers.json"), 2u);
  const auto local_cases = cases(dir_ / "local"), slurm_cases = cases(dir_ / "slurm");
  ASSERT_EQ(local_cases.size(), 6u);
  ASSERT_EQ(slurm_cases.size(), 6u);
  for (std::size_t i = 0; i < 6; ++i) {
    EXPECT_EQ(local_cases[i].filename(), slurm_cases[i].filename());
    for (const char* file :
         {"collide/fibers.json", "molds/shot1-upper.stl", "molds/shot2-lower.stl", "export/manifest.json"})
      EXPECT_EQ(test::read_text(local_cases[i] / file), test::read_text(slurm_cases[i] / file))
          << slurm_cases[i] << " " << file;
  }

  // A longer optimization, submitted without waiting; one of its two tasks is cancelled while it runs.
  // (40 iterations raced the cancel once the optimization ran on one BLAS thread: a task finished
  // before scancel reached it.)
  test::write_text(dir_ / "sweep.toml",
                   std::string(kSweep).replace(std::string(kSweep).find("[3, 5]"), 6, "[120, 121]"));
  const auto submitted = sweep("--engine slurm --build-dir killed --no-wait", slurm.env());
  ASSERT_EQ(submitted.exit_code, 0) << submitted.out << submitted.err;
  std::smatch job;
  const std::string out = submitted.out;
  ASSERT_TRUE(std::regex_search(out, job, std::regex("optimize: 2 task\\(s\\), Slurm job (\\d+)"))) << out;
  std::string running;
  for (int i = 0; i < 600 && running.empty(); ++i, std::this_thread::sleep_for(std::chrono::milliseconds(100))) {
    std::istringstream q(slurm.run("squeue -h -r -o '%i %T' -j " + job[1].str()));
    for (std::string task, state; q >> task >> state;)
      if (state == "RUNNING") running = task;
  }
  ASSERT_FALSE(running.empty()) << "the optimize tasks never ran";
  const auto while_running = sweep("--status --build-dir killed", slurm.env());
  EXPECT_THAT(while_running.out, ::testing::ContainsRegex("case [0-9a-f]{10}: RUNNING"));
  EXPECT_THAT(while_running.out, HasSubstr("task(s) still queued or running"));
  const auto again = sweep("--engine slurm --build-dir killed", slurm.env());
  EXPECT_EQ(again.exit_code, 1);
  EXPECT_THAT(again.err, HasSubstr("still queued or running"));
  slurm.run("scancel " + running);
  for (int i = 0; i < 1200 && !slurm.run("squeue -h -o %i").empty(); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  const auto status = sweep("--status --build-dir killed", slurm.env());
  EXPECT_EQ(status.exit_code, 1);
  EXPECT_THAT(status.out, HasSubstr("optimize  1 of 2 built:"));
  EXPECT_THAT(status.out, ::testing::ContainsRegex("case [0-9a-f]{10}: failed or not run"));
  const auto rerun = sweep("--engine slurm --build-dir killed", slurm.env());
  ASSERT_EQ(rerun.exit_code, 0) << rerun.out << rerun.err;
  EXPECT_THAT(rerun.out, HasSubstr("optimize: 1 task(s)"));
  EXPECT_THAT(rerun.out, ::testing::Not(HasSubstr("mesh:")));
  EXPECT_THAT(rerun.out, HasSubstr("export    6 of 6 built"));
}

} // namespace
} // namespace fibermold
