// The Make-style runner with test-only stages in a temporary build folder (docs/architecture.md, "Tests").
#include "make/runner.hpp"

#include <algorithm>
#include <csignal>
#include <functional>
#include <map>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include "core/input_error.hpp"
#include "design/design_file.hpp"
#include "make/build_lock.hpp"
#include "test_support.hpp"

namespace fibermold {
namespace {

namespace fs = std::filesystem;
using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::IsEmpty;

using Hook = std::function<void(StageContext&)>;

/// A stage that writes out.txt from the design values it reads (or a subset), its input files and
/// its upstream outputs, so that every kind of input shows in its output. Counts its runs.
class FakeStage final : public Stage {
public:
  struct Spec {
    std::string name;
    std::vector<std::string> upstream;
    std::vector<std::string> keys;
    std::vector<std::string> output_keys; ///< keys whose values reach the output; empty: all of `keys`
    bool reads_surface = false;
    int version = 1;
  };

  FakeStage(Spec spec, std::map<std::string, int>& runs, std::map<std::string, Hook>& hooks)
      : spec_(std::move(spec)), runs_(runs), hooks_(hooks)
  {
  }

  std::string name() const override { return spec_.name; }
  std::vector<std::string> upstream() const override { return spec_.upstream; }
  std::vector<std::string> design_keys() const override { return spec_.keys; }
  std::vector<fs::path> input_files(const Design& d) const override
  {
    return spec_.reads_surface ? std::vector<fs::path>{d.design.surface} : std::vector<fs::path>{};
  }
  int version() const override { return spec_.version; }

  void run(StageContext& ctx) const override
  {
    ++runs_[spec_.name];
    if (auto hook = hooks_.find(spec_.name); hook != hooks_.end()) hook->second(ctx);
    std::string content = spec_.name + "\n";
    const auto& keys = spec_.output_keys.empty() ? spec_.keys : spec_.output_keys;
    for (const auto& [key, value] : ctx.design.values)
      for (const std::string& prefix : keys)
        if (design_key_matches(key, prefix)) content += key + "=" + value + "\n";
    if (spec_.reads_surface) content += test::read_text(ctx.design.design.surface);
    for (const std::string& up : spec_.upstream) content += test::read_text(ctx.upstream(up, "out.txt"));
    test::write_text(ctx.output_dir / "out.txt", content);
  }

private:
  Spec spec_;
  std::map<std::string, int>& runs_;
  std::map<std::string, Hook>& hooks_;
};

const char* kDesign = R"([design]
surface = "body.stl"
[mesh]
edge_length = 4.0
repair = false
[[fiber]]
name = "m1"
points = [[0, 0, 0], [10, 0, 0]]
[optimize]
max_iterations = 10
[collide]
clearance = 1.0
[mold]
wall = 4.0
[export]
formats = ["stl"]
)";

class RunnerTest : public ::testing::Test {
protected:
  void SetUp() override
  {
    test::write_text(dir_ / "body.stl", "surface v1\n");
    text_ = kDesign;
  }
  void TearDown() override { clear_interrupt(); }

  Design design()
  {
    test::write_text(dir_ / "design.toml", text_);
    return load_design(dir_ / "design.toml");
  }

  void edit(const std::string& from, const std::string& to)
  {
    const auto at = text_.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    text_.replace(at, from.size(), to);
  }

  Runner runner(const std::string& program = "fibermold test", int molds_version = 1)
  {
    std::vector<std::unique_ptr<Stage>> stages;
    const auto add = [&](FakeStage::Spec spec) {
      stages.push_back(std::make_unique<FakeStage>(std::move(spec), runs_, hooks_));
    };
    // Registered out of order on purpose: the runner sorts by dependency.
    add({"export", {"molds"}, {"export"}, {}, false, 1});
    add({"mesh", {}, {"design.surface", "design.units", "mesh"}, {"design.surface", "mesh.edge_length"}, true, 1});
    add({"targets", {"mesh"}, {"material", "target"}, {}, false, 1});
    add({"optimize", {"targets"}, {"optimize", "fiber"}, {}, false, 1});
    add({"collide", {"optimize"}, {"collide"}, {}, false, 1});
    add({"molds", {"collide"}, {"mold"}, {}, false, molds_version});
    return Runner(std::move(stages), program);
  }

  /// Names of the stages that ran in `runs`.
  static std::vector<std::string> ran(const std::vector<StageRun>& runs)
  {
    std::vector<std::string> names;
    for (const StageRun& r : runs)
      if (r.ran) names.push_back(r.stage);
    return names;
  }

  std::vector<std::string> make(const Runner& r, std::vector<std::string> targets = {}, bool force = false)
  {
    return ran(r.make(design(), {build_, std::move(targets), force}));
  }

  /// Stale stages, each with its first reason.
  std::map<std::string, std::string> stale(const Runner& r)
  {
    std::map<std::string, std::string> result;
    for (const StageStatus& s : r.status(design(), build_))
      if (!s.fresh) result[s.stage] = s.reasons.empty() ? "" : s.reasons.front();
    return result;
  }

  std::string output(const std::string& stage) { return test::read_text(build_ / stage / "out.txt"); }

  test::TempDir dir_;
  fs::path build_ = dir_ / "build";
  std::string text_;
  std::map<std::string, int> runs_;
  std::map<std::string, Hook> hooks_;
};

TEST_F(RunnerTest, OrdersStagesByDependency)
{
  EXPECT_THAT(runner().stage_names(), ElementsAre("mesh", "targets", "optimize", "collide", "molds", "export"));
}

TEST_F(RunnerTest, FirstMakeRunsEverythingSecondNothing)
{
  const Runner r = runner();
  EXPECT_EQ(stale(r).at("mesh"), "never built");
  EXPECT_THAT(make(r), ElementsAre("mesh", "targets", "optimize", "collide", "molds", "export"));
  EXPECT_THAT(stale(r), IsEmpty());
  EXPECT_THAT(make(r), IsEmpty());
  EXPECT_EQ(runs_["mesh"], 1);
  EXPECT_THAT(output("export"), HasSubstr("[mold].wall=4"));
  EXPECT_THAT(output("export"), HasSubstr("surface v1"));
  EXPECT_FALSE(fs::exists(build_ / ".staging")) << "an empty staging folder left in the build folder";
}

TEST_F(RunnerTest, DownstreamEditRerunsOnlyDownstream)
{
  const Runner r = runner();
  make(r);
  edit("wall = 4.0", "wall = 5.0");
  const auto s = stale(r);
  EXPECT_EQ(s.size(), 2u);
  EXPECT_EQ(s.at("molds"), "[mold].wall changed (4 → 5)");
  EXPECT_EQ(s.at("export"), "upstream molds is stale");
  EXPECT_THAT(make(r), ElementsAre("molds", "export"));
  EXPECT_THAT(output("export"), HasSubstr("[mold].wall=5"));
}

TEST_F(RunnerTest, EachKindOfInputChangeMakesExactlyTheRightStagesStale)
{
  const Runner r = runner();
  make(r);

  edit("max_iterations = 10", "max_iterations = 20"); // a design value of a middle stage
  EXPECT_EQ(stale(r).at("optimize"), "[optimize].max_iterations changed (10 → 20)");
  EXPECT_THAT(make(r), ElementsAre("optimize", "collide", "molds", "export"));

  edit("[10, 0, 0]", "[12, 0, 0]"); // an array-of-tables entry
  EXPECT_THAT(stale(r).at("optimize"), HasSubstr("[fiber.m1].points changed"));
  EXPECT_THAT(make(r), ElementsAre("optimize", "collide", "molds", "export"));

  test::write_text(dir_ / "body.stl", "surface v2\n"); // an input file's content
  EXPECT_EQ(stale(r).at("mesh"), "file body.stl changed");
  EXPECT_EQ(stale(r).size(), 6u);
  EXPECT_EQ(make(r).size(), 6u);

  edit("[collide]\nclearance = 1.0", "[collide]\nclearance = 1.0\nreoptimize = true"); // a key added
  EXPECT_EQ(stale(r).at("collide"), "[collide].reoptimize changed (false → true)");
  EXPECT_THAT(make(r), ElementsAre("collide", "molds", "export"));

  edit("[[fiber]]\nname = \"m1\"\npoints = [[0, 0, 0], [12, 0, 0]]\n", ""); // an entry removed
  EXPECT_EQ(stale(r).at("optimize"), "[fiber.m1].name removed");
  EXPECT_THAT(make(r), ElementsAre("optimize", "collide", "molds", "export"));
  EXPECT_THAT(stale(r), IsEmpty());
}

// A stage stale for many reasons says the first three and how many more on the terminal (a line,
// not a screenful); logs/make.log keeps them all.
TEST_F(RunnerTest, AStaleStageSaysItsFirstReasonsAndHowManyMoreAndTheLogKeepsAll)
{
  const Runner r = runner();
  make(r);
  edit("max_iterations = 10",
       "max_iterations = 20\nstarts = 2\nmethod = \"bfgs\"\nroute_only_iterations = 3\nrefine = true");
  const std::vector<StageStatus> statuses = r.status(design(), build_);
  const auto optimize = std::find_if(statuses.begin(), statuses.end(), [](auto& s) { return s.stage == "optimize"; });
  ASSERT_NE(optimize, statuses.end());
  ASSERT_EQ(optimize->reasons.size(), 5u);
  EXPECT_EQ(optimize->summary(),
            fmt::format("{}; {}; {}; and 2 more", optimize->reasons[0], optimize->reasons[1], optimize->reasons[2]));
  EXPECT_EQ(optimize->summary(5), fmt::format("{}", fmt::join(optimize->reasons, "; ")));
  make(r);
  const std::string log = test::read_text(Runner::make_log_path(build_));
  EXPECT_THAT(log, HasSubstr(fmt::format("optimize stale: {}", fmt::join(optimize->reasons, "; "))));
}

TEST_F(RunnerTest, ProgramAndStageVersionsAreInputs)
{
  make(runner("fibermold 1"));
  EXPECT_THAT(stale(runner("fibermold 1")), IsEmpty());
  EXPECT_EQ(stale(runner("fibermold 2")).at("mesh"), "program version changed (fibermold 1 → fibermold 2)");
  EXPECT_EQ(stale(runner("fibermold 2")).size(), 6u);
  const auto s = stale(runner("fibermold 1", 2));
  EXPECT_EQ(s.size(), 2u);
  EXPECT_EQ(s.at("molds"), "stage algorithm changed (v1 → v2)");
}

TEST_F(RunnerTest, UnchangedUpstreamOutputDoesNotRerunDownstream)
{
  const Runner r = runner();
  make(r);
  edit("repair = false", "repair = true"); // mesh reads it, but its output does not change
  EXPECT_THAT(make(r), ElementsAre("mesh"));
  EXPECT_THAT(stale(r), IsEmpty());
}

TEST_F(RunnerTest, ModifiedOrMissingOutputMakesItsStageStale)
{
  const Runner r = runner();
  make(r);
  test::write_text(build_ / "collide" / "out.txt", "tampered");
  EXPECT_EQ(stale(r).at("collide"), "output collide/out.txt was modified");
  EXPECT_THAT(make(r), ElementsAre("collide")); // the rerun restores the same output
  fs::remove(build_ / "molds" / "out.txt");
  EXPECT_EQ(stale(r).at("molds"), "output molds/out.txt is missing");
  EXPECT_THAT(make(r), ElementsAre("molds"));
}

TEST_F(RunnerTest, MakeStopsAtTheNamedStage)
{
  const Runner r = runner();
  EXPECT_THAT(make(r, {"optimize"}), ElementsAre("mesh", "targets", "optimize"));
  EXPECT_THAT(make(r, {"collide"}), ElementsAre("collide"));
  EXPECT_FALSE(fs::exists(build_ / "molds"));
}

TEST_F(RunnerTest, ForceRerunsFreshStages)
{
  const Runner r = runner();
  make(r);
  EXPECT_THAT(make(r, {"targets"}, true), ElementsAre("mesh", "targets"));
}

TEST_F(RunnerTest, UnknownStageNameIsAnInputErrorWithHint)
{
  const Runner r = runner();
  try {
    make(r, {"mold"});
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("unknown stage 'mold'; did you mean 'molds'?"));
  }
}

TEST_F(RunnerTest, CleanMakesTheStageAndDownstreamStale)
{
  const Runner r = runner();
  make(r);
  r.clean(build_, {"collide"});
  EXPECT_FALSE(fs::exists(build_ / "collide"));
  const auto s = stale(r);
  EXPECT_EQ(s.size(), 3u);
  EXPECT_EQ(s.at("collide"), "never built");
  EXPECT_EQ(s.at("molds"), "upstream collide is stale");
  r.clean(build_);
  EXPECT_EQ(stale(r).size(), 6u);
  EXPECT_FALSE(fs::exists(build_ / "mesh"));
}

TEST_F(RunnerTest, FailedStageKeepsPreviousOutputsByteIdenticalAndStaysStale)
{
  const Runner r = runner();
  make(r);
  const std::string before = output("molds");
  edit("wall = 4.0", "wall = 6.0");
  hooks_["molds"] = [](StageContext& ctx) {
    test::write_text(ctx.output_dir / "out.txt", "half a fi");
    throw std::runtime_error("the cavity is not closed");
  };
  try {
    make(r);
    FAIL() << "expected StageFailed";
  } catch (const StageFailed& e) {
    EXPECT_EQ(e.stage(), "molds");
    EXPECT_THAT(e.what(), HasSubstr("the cavity is not closed"));
    EXPECT_THAT(test::read_text(e.log()), HasSubstr("the cavity is not closed"));
  }
  EXPECT_EQ(output("molds"), before);
  EXPECT_EQ(runs_["export"], 1); // not run after the failure
  EXPECT_EQ(stale(r).at("molds"), "last run failed or was interrupted");
  EXPECT_THAT(test::read_text(Runner::make_log_path(build_)), HasSubstr("molds failed"));

  hooks_.clear();
  EXPECT_THAT(make(r), ElementsAre("molds", "export"));
  EXPECT_THAT(output("molds"), HasSubstr("[mold].wall=6"));
}

// A stage that writes a value it did not compute (here a JSON null, what nlohmann writes for a NaN)
// fails as a bug, naming the file and line, and none of its outputs replace the previous ones.
TEST_F(RunnerTest, AStageThatWritesANanOrNullFailsAndKeepsNothing)
{
  const Runner r = runner();
  make(r);
  const std::string before = output("molds");
  edit("wall = 4.0", "wall = 6.0");
  hooks_["molds"] = [](StageContext& ctx) {
    test::write_text(ctx.output_dir / "report.json", "{\n  \"wall_mm\": 6.0,\n  \"volume_mL\": null\n}\n");
  };
  try {
    make(r);
    FAIL() << "expected StageFailed";
  } catch (const StageFailed& e) {
    EXPECT_EQ(e.stage(), "molds");
    EXPECT_THAT(e.what(), HasSubstr("wrote a value it did not compute (NaN, an infinity, a JSON null or a design "
                                    "value it did not declare) into report.json, line 3: "));
    EXPECT_THAT(e.what(), HasSubstr("This is a bug in fibermold"));
  }
  EXPECT_EQ(output("molds"), before);
  EXPECT_FALSE(fs::exists(build_ / "molds" / "report.json"));
  EXPECT_EQ(stale(r).at("molds"), "last run failed or was interrupted");
}

TEST_F(RunnerTest, InterruptedStageKeepsPreviousOutputsAndStaysStale)
{
  const Runner r = runner();
  make(r);
  const std::string before = output("optimize");
  edit("max_iterations = 10", "max_iterations = 11");
  hooks_["optimize"] = [](StageContext& ctx) {
    test::write_text(ctx.output_dir / "out.txt", "partial");
    request_interrupt(); // as the SIGINT handler does
    ctx.progress.checkpoint(0.5, "iteration 5");
  };
  EXPECT_THROW(make(r), Interrupted);
  EXPECT_EQ(output("optimize"), before);
  EXPECT_EQ(stale(r).at("optimize"), "last run failed or was interrupted");
  EXPECT_FALSE(fs::exists(build_ / ".staging" / "optimize"));
}

TEST_F(RunnerTest, StageKilledMidWriteLeavesPreviousOutputsByteIdentical)
{
  const Runner r = runner();
  make(r);
  const std::string before = output("molds");
  edit("wall = 4.0", "wall = 7.0");
  const Design d = design();

  int pipe_fds[2];
  ASSERT_EQ(::pipe(pipe_fds), 0);
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    ::close(pipe_fds[0]);
    hooks_["molds"] = [&](StageContext& ctx) {
      test::write_text(ctx.output_dir / "out.txt", "half writt");
      const char ready = 'w';
      [[maybe_unused]] auto n = ::write(pipe_fds[1], &ready, 1);
      for (;;) ::pause(); // killed here, mid-stage
    };
    try {
      r.make(d, {build_, {}, false});
    } catch (...) {
    }
    ::_exit(3);
  }
  ::close(pipe_fds[1]);
  char ready = 0;
  ASSERT_EQ(::read(pipe_fds[0], &ready, 1), 1);
  ::close(pipe_fds[0]);
  ASSERT_EQ(::kill(child, SIGKILL), 0);
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFSIGNALED(status));

  EXPECT_EQ(output("molds"), before);
  EXPECT_EQ(stale(r).at("molds"), "last run failed or was interrupted");
  EXPECT_EQ(stale(r).at("export"), "upstream molds is stale");
  EXPECT_THAT(make(r), ElementsAre("molds", "export")); // the lock died with the child
  EXPECT_THAT(output("molds"), HasSubstr("[mold].wall=7"));
  EXPECT_FALSE(fs::exists(build_ / ".staging" / "molds"));
}

TEST_F(RunnerTest, SecondConcurrentMakeIsRefused)
{
  const Runner r = runner();
  int to_parent[2], to_child[2];
  ASSERT_EQ(::pipe(to_parent), 0);
  ASSERT_EQ(::pipe(to_child), 0);
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    BuildLock lock(build_); // as a running make holds it
    const char ready = 'l';
    [[maybe_unused]] auto w = ::write(to_parent[1], &ready, 1);
    char done = 0;
    [[maybe_unused]] auto rd = ::read(to_child[0], &done, 1);
    ::_exit(0);
  }
  char ready = 0;
  ASSERT_EQ(::read(to_parent[0], &ready, 1), 1);
  try {
    make(r);
    ADD_FAILURE() << "expected BuildLocked";
  } catch (const BuildLocked& e) {
    EXPECT_THAT(e.what(), HasSubstr("another fibermold (pid " + std::to_string(child) + ") is working in"));
  }
  EXPECT_EQ(runs_["mesh"], 0);
  EXPECT_THROW(r.clean(build_), BuildLocked);
  const char done = 'd';
  ASSERT_EQ(::write(to_child[1], &done, 1), 1);
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  EXPECT_EQ(make(r).size(), 6u);
}

TEST(RunnerGraph, RejectsCyclesDuplicatesAndUnknownUpstream)
{
  std::map<std::string, int> runs;
  std::map<std::string, Hook> hooks;
  const auto stages = [&](std::vector<FakeStage::Spec> specs) {
    std::vector<std::unique_ptr<Stage>> out;
    for (auto& s : specs) out.push_back(std::make_unique<FakeStage>(s, runs, hooks));
    return out;
  };
  EXPECT_THROW(Runner(stages({{"a", {"b"}, {}, {}}, {"b", {"a"}, {}, {}}})), std::logic_error);
  EXPECT_THROW(Runner(stages({{"a", {}, {}, {}}, {"a", {}, {}, {}}})), std::logic_error);
  EXPECT_THROW(Runner(stages({{"a", {"zzz"}, {}, {}}})), std::logic_error);
}

} // namespace
} // namespace fibermold
