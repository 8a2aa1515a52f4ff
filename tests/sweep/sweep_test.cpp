// The sweep file and its cases: the product of the axes or listed cases, each value put into the
// base design, random restarts that keep the end points, case names that follow the design's
// content, and problems reported at the sweep file's line.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/input_error.hpp"
#include "design/design_file.hpp"
#include "make/runner.hpp"
#include "stages/stages.hpp"
#include "sweep/sweep_cases.hpp"
#include "sweep/sweep_file.hpp"
#include "test_support.hpp"

namespace fibermold {
namespace {

using ::testing::HasSubstr;

const std::string kBase = std::string(test::kBarDesign) + test::kBarMuscle + "[mold]\nwall = 4.0\n";

class Sweep : public ::testing::Test {
protected:
  void SetUp() override
  {
    test::write_bar(dir_.path());
    test::write_text(dir_ / "design.toml", kBase);
  }
  SweepFile sweep(const std::string& text)
  {
    test::write_text(dir_ / "sweep.toml", "[sweep]\ndesign = \"design.toml\"\n" + text);
    return load_sweep(dir_ / "sweep.toml");
  }
  /// The problems of a sweep (file, expansion), one per line.
  std::string problems(const std::string& text)
  {
    try {
      expand_sweep(sweep(text));
    } catch (const InputError& e) {
      std::string out;
      for (const Diagnostic& d : e.diagnostics()) out += d.to_string() + "\n";
      return out;
    }
    return "";
  }
  Design design_of(const SweepCase& c) { return parse_design(c.design, dir_ / "cases" / c.id / "design.toml"); }

  test::TempDir dir_;
};

TEST_F(Sweep, ProductOfTheAxesPutsEachValueIntoTheBaseDesign)
{
  const SweepFile s = sweep("[axes]\n\"mold.wall\" = [3, 5]\n\"muscle.max_pressure\" = [300, 350, 425]\n");
  EXPECT_EQ(s.axes, (std::vector<std::string>{"mold.wall", "muscle.max_pressure"}));
  const std::vector<SweepCase> cases = expand_sweep(s);
  ASSERT_EQ(cases.size(), 6u);
  std::set<std::string> ids;
  for (const SweepCase& c : cases) {
    const Design d = design_of(c);
    EXPECT_NEAR(d.mold.block.wall, std::stod(c.values[0]) * 1e-3, 1e-12) << c.id;
    EXPECT_NEAR(d.muscle.max_pressure, std::stod(c.values[1]) * 1e3, 1e-9) << c.id;
    EXPECT_EQ(d.design.name, "bar");
    EXPECT_EQ(d.design.surface, (dir_ / "bar.stl").lexically_normal()); // absolute: the case works from its own folder
    ids.insert(c.id);
  }
  EXPECT_EQ(ids.size(), 6u);
  EXPECT_EQ(expand_sweep(s)[3].id, cases[3].id); // named by content: the same design, the same folder
}

TEST_F(Sweep, ListedCasesAndAnArraySectionsKey)
{
  const std::vector<SweepCase> cases = expand_sweep(
      sweep("[[case]]\n\"mold.wall\" = 3\n[[case]]\n\"fiber.m1.points\" = [[0, 0, 0], [30, 1, 1], [60, 0, 0]]\n"));
  ASSERT_EQ(cases.size(), 2u);
  EXPECT_NEAR(design_of(cases[0]).mold.block.wall, 3e-3, 1e-12);
  EXPECT_EQ(cases[0].values, (std::vector<std::string>{"3", ""}));
  const Design second = design_of(cases[1]);
  ASSERT_EQ(second.fibers[0].points.size(), 3u);
  EXPECT_NEAR(second.fibers[0].points[1].x(), 30e-3, 1e-12);
  EXPECT_NEAR(second.mold.block.wall, 4e-3, 1e-12);
}

TEST_F(Sweep, RestartsMoveInteriorPointsWithinTheAmplitudeAndKeepTheEnds)
{
  const std::vector<SweepCase> cases = expand_sweep(sweep("[restarts]\ncount = 4\nseed = 7\namplitude = 1.5\n"));
  ASSERT_EQ(cases.size(), 4u);
  const Design base = load_design(dir_ / "design.toml");
  for (const SweepCase& c : cases) {
    const Design d = design_of(c);
    const auto& p = d.fibers[0].points;
    const auto& q = base.fibers[0].points;
    EXPECT_EQ(p.front(), q.front());
    EXPECT_EQ(p.back(), q.back());
    for (std::size_t i = 1; i + 1 < p.size(); ++i) {
      const double moved = (p[i] - q[i]).norm();
      if (c.values.back() == "0")
        EXPECT_EQ(moved, 0);
      else
        EXPECT_GT(moved, 0);
      EXPECT_LE(moved, 1.5e-3 + 1e-9);
    }
  }
  EXPECT_EQ(expand_sweep(load_sweep(dir_ / "sweep.toml"))[2].design, cases[2].design); // the seed decides
  EXPECT_NE(expand_sweep(sweep("[restarts]\ncount = 4\nseed = 8\namplitude = 1.5\n"))[2].design, cases[2].design);
}

TEST_F(Sweep, CasesThatDifferInMoldValuesShareEveryStageUpToCollide)
{
  const std::vector<SweepCase> cases = expand_sweep(sweep("[axes]\n\"mold.wall\" = [3, 5]\n"));
  const Runner runner(shipped_stages());
  const auto a = runner.fingerprints(design_of(cases[0])), b = runner.fingerprints(design_of(cases[1]));
  for (const std::string stage : {"mesh", "targets", "optimize", "collide"})
    EXPECT_EQ(a.at(stage), b.at(stage)) << stage;
  for (const std::string stage : {"molds", "export"}) EXPECT_NE(a.at(stage), b.at(stage)) << stage;
}

TEST_F(Sweep, ProblemsAreReportedAtTheSweepFilesLine)
{
  const std::string file = (dir_ / "sweep.toml").string();
  EXPECT_THAT(problems("[axes]\n\"mold.wal\" = [3, 4]\n"),
              HasSubstr(file + ":4:15: \"mold.wal\" = 3: unknown key 'wal' in [mold]"));
  EXPECT_THAT(problems("[axes]\n\"mold.wall\" = [3, -4]\n"),
              HasSubstr(file + ":4:19: \"mold.wall\" = -4: must be in (0, 1000] mm"));
  EXPECT_THAT(problems("[axes]\n\"fiber.m2.points\" = [[[0, 0, 0], [60, 0, 0]]]\n"),
              HasSubstr(file + ":4:22: \"fiber.m2.points\": the base design has no [[fiber]] named 'm2' (it has: m1)"));
  EXPECT_THAT(problems("[axes]\nwall = [3]\n"),
              HasSubstr(file + ":4:8: [axes].\"wall\": a design-file key names its section"));
  EXPECT_THAT(problems("[axes]\n\"mold.wall\" = 3\n"), HasSubstr("needs a non-empty list of values"));
  EXPECT_THAT(problems("[axes]\n\"mold.wall\" = [3]\n[[case]]\n\"mold.wall\" = 3\n"), HasSubstr("not both"));
  EXPECT_THAT(problems("[restarts]\ncount = \"4\"\n"),
              HasSubstr(file + ":4:9: [restarts].count: needs a whole number in [1, 1000]"));
  EXPECT_THAT(problems("[slurm]\npartiton = \"long\"\n"),
              HasSubstr("unknown key 'partiton' in [slurm]; did you mean 'partition'?"));
  EXPECT_THAT(problems("[axes]\n\"mold.wall\" = [3, 3]\n"), HasSubstr("makes the same design as an earlier case"));
  EXPECT_THAT(problems("name = \"../x\"\n"), HasSubstr(file + ":3:8: [sweep].name: \"../x\" cannot name a folder"));
  EXPECT_THAT(problems("[slurm]\ncpus_per_task = 0\n"),
              HasSubstr("[slurm].cpus_per_task: needs a whole number of at least 1"));
  EXPECT_THAT(problems("[slurm]\ntime = \"1:00\\n#SBATCH --x\"\n"), HasSubstr("is not a Slurm time"));
  EXPECT_THAT(problems("[[axes]]\n\"mold.wall\" = [3]\n"), HasSubstr("axes: needs a table: [axes]"));
  EXPECT_THAT(problems("[restarts]\ncount = 2\nfibers = [\"m9\"]\n"),
              HasSubstr(file + ":5: [restarts].fibers: the base design has no [[fiber]] named 'm9'"));
}

} // namespace
} // namespace fibermold
