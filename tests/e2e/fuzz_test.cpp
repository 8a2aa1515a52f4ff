// The command line fed as the world will feed it (tests/mutants.hpp, tests/fuzz.hpp): mutants of a
// small design and of its surface through `check`, and those that check passes through `make`.
// bench/fuzz_bench runs thousands; these few hundred keep every rule in the suite.

#include <map>

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "export/stl_writer.hpp"
#include "fuzz.hpp"
#include "mutants.hpp"
#include "primitives.hpp"
#include "test_support.hpp"

namespace fibermold {
namespace {

using ::testing::HasSubstr;
using ::testing::MatchesRegex;
namespace fs = std::filesystem;

/// The bar with its muscle, curve and target; two optimizer iterations and coarse molds keep a
/// whole make near 10 s.
const std::string kDesign = std::string(test::kBarDesign) + test::kBarMuscle + test::kBarTrackingCurve +
                            test::kBarTarget +
                            "[optimize]\nmax_iterations = 2\n[mold]\nvoxel = 0.6\nwall = 3\nkeys = 2\n";

SurfaceMesh bar() { return test::box({0, -0.008, -0.008}, {0.06, 0.008, 0.008}, Eigen::Vector3i(10, 3, 3)); }

/// Runs every mutant; `make_limit`: how many of those check passes go on through make.
std::map<int, int> fuzz(const std::vector<test::Mutant>& mutants, bool mesh, int make_limit)
{
  std::map<int, int> codes; // check's exit code → count; make's as 100 + code
  int made = 0;
  for (const test::Mutant& m : mutants) {
    test::TempDir dir;
    if (mesh) {
      test::write_text(dir / "design.toml", kDesign);
      test::write_text(dir / "bar.stl", m.text);
    } else {
      test::write_text(dir / "design.toml", m.text);
      write_stl(dir / "bar.stl", bar());
    }
    const bool make = made < make_limit;
    const test::FuzzRun r = test::fuzz_run(dir.path(), make, 30, 180);
    ++codes[r.check];
    if (r.make >= 0) ++codes[100 + r.make], ++made;
    EXPECT_EQ(r.problem, "") << m.what;
  }
  return codes;
}

TEST(FuzzE2E, DesignMutantsKeepTheExitCodesAndWriteNoNull)
{
  const auto mutants = test::design_mutants(kDesign, 240, 28);
  const auto codes = fuzz(mutants, false, 6);
  for (const auto& [code, count] : codes)
    fmt::print("  {} {}: {}\n", code >= 100 ? "make" : "check", code % 100, count);
  // The generator is not toothless: it makes both designs check refuses and designs it passes
  // (24 of 240 pass since [muscle] min_bend_radius: a moved control point of the bar's muscle, whose
  // tightest bend is 11.4 mm, often bends it under 9 mm; 30 or more passed before).
  EXPECT_GT(codes.count(2) ? codes.at(2) : 0, 60);
  EXPECT_GT(codes.count(0) ? codes.at(0) : 0, 20);
}

TEST(FuzzE2E, MeshMutantsKeepTheExitCodes)
{
  test::TempDir dir;
  write_stl(dir / "bar.stl", bar());
  const auto mutants = test::mesh_mutants(test::read_text(dir / "bar.stl"), 80, 28);
  const auto codes = fuzz(mutants, true, 2);
  for (const auto& [code, count] : codes)
    fmt::print("  {} {}: {}\n", code >= 100 ? "make" : "check", code % 100, count);
  EXPECT_GT(codes.count(2) ? codes.at(2) : 0, 20);
}

/// What fuzzing found once (issue #28), each refused by check with exit 2 at its line.
TEST(FuzzE2E, OnceFoundReproducersAreRefusedAtTheirLine)
{
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"points = [[0, 0, 0], [20, 3, -3]", "points = [[0, 0, 0], [1e308, 3, -3]"},
      {"points = [[0, 0, 0], [60, 0, 0]]", "points = [[0, 0, 0], [60, 1e308, 0]]"},
      {"voxel = 0.6", "voxel = 0.01"},
      {"[optimize]\n", "[muscle]\ndiameter = 1e9\n[optimize]\n"},
      {"[optimize]\n", "[muscle]\ndiameter = 5e-324\n[optimize]\n"},
      {"[optimize]\n", "[muscle]\ndiameter = 2147483647\n[optimize]\n"},
      {"[optimize]\n", "[material]\npoisson_ratio = 9223372036854775807\n[optimize]\n"},
      {"[optimize]\n", "[material]\ndensity = 1e308\n[optimize]\n"},
      {"kind = \"fibers\"", "kind = \"Fibers\""},
      {"name = \"bar\"", "name = \"" + std::string(5000, 'b') + "\""},
      {"surface = \"bar.stl\"", "surface = \"bar.stl\\u0000x\""},
  };
  for (const auto& [from, to] : cases) {
    test::TempDir dir;
    std::string design = kDesign;
    ASSERT_NE(design.find(from), std::string::npos) << from;
    design.replace(design.find(from), from.size(), to);
    test::write_text(dir / "design.toml", design);
    write_stl(dir / "bar.stl", bar());
    const auto r = test::run_fibermold("check design.toml", dir.path());
    EXPECT_EQ(r.exit_code, 2) << to << "\n" << r.out << r.err;
    EXPECT_THAT(r.err, MatchesRegex(".*design\\.toml:[0-9]+:[0-9]+: .*")) << to;
    EXPECT_LT(r.err.size(), 600u) << to;
  }
}

/// bench/fuzz_bench found it (a design cut short after its [mesh]): check passed a design without a
/// fiber, which the optimize stage then refused as bad input. check now asks what optimize asks.
TEST(FuzzE2E, CheckRefusesWhatOptimizeWouldRefuse)
{
  test::TempDir dir;
  std::string design = kDesign;
  design.erase(design.find(test::kBarMuscle), std::string(test::kBarMuscle).size());
  test::write_text(dir / "design.toml", design);
  write_stl(dir / "bar.stl", bar());
  const auto r = test::run_fibermold("check design.toml", dir.path());
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  EXPECT_THAT(r.err, HasSubstr("design.toml: [[fiber]]: nothing to optimize: give at least one fiber"));
  // A tracking curve out of the body, found by the optimize stage before: check finds it now, at its line.
  design = kDesign;
  design.replace(design.find("[60, 0, 0]]\nsamples"), 10, "[60, 0, 12]");
  test::write_text(dir / "design.toml", design);
  const auto out = test::run_fibermold("check design.toml", dir.path());
  EXPECT_EQ(out.exit_code, 2) << out.out << out.err;
  EXPECT_THAT(out.err, ::testing::ContainsRegex(
                           "design\\.toml:[0-9]+:[0-9]+: \\[tracking_curve\\.centre\\]\\.points\\[2\\]: the curve "
                           "leaves the body at"));
}

/// The rule on the designs users start from: mutants of each example's design (made cheap: coarse
/// meshes and voxels, two optimizer iterations) through check; of those check passes, the first
/// two per example through every stage of make, which must not refuse them as bad input.
TEST(FuzzE2E, MutantsOfEveryExampleThatCheckPassesMakeDoesNotRefuse)
{
  struct Example {
    std::string folder, design;
    std::vector<std::pair<std::string, std::string>> cheap;
  };
  const std::vector<Example> examples = {
      {"twisting-bar",
       "design.toml",
       {{"max_iterations = 1000", "max_iterations = 2"},
        {"route_only_iterations = 30 ", "route_only_iterations = 1 "},
        {"voxel = 0.2 ", "voxel = 0.6 "}}},
      {"hand-routed-twist",
       "design.toml",
       {{"voxel = 0.25", "voxel = 0.6"},
        {"\"../twisting-bar/bar.stl\"",
         "\"" + (fs::path(FIBERMOLD_SOURCE_DIR) / "examples" / "twisting-bar" / "bar.stl").string() + "\""}}},
      {"recovery",
       "design.toml",
       {{"edge_length = 5.0", "edge_length = 8.0"}, {"max_iterations = 400", "max_iterations = 2"}}},
      {"walking-robot",
       "design.toml",
       {{"edge_length = 5.0", "edge_length = 6.0"},
        {"max_iterations = 100", "max_iterations = 2"},
        {"voxel = 0.2 ", "voxel = 0.5 "}}},
      {"notched-finger",
       "design.toml",
       {{"edge_length = 4.0", "edge_length = 6.0"},
        {"max_iterations = 200", "max_iterations = 2"},
        {"voxel = 0.25", "voxel = 0.6"}}},
      {"continuum-robot",
       "design.toml",
       {{"max_iterations = 200", "max_iterations = 2"}, {"voxel = 0.25", "voxel = 0.8"}}},
  };
  std::map<int, int> codes;
  for (const Example& e : examples) {
    const fs::path source = fs::path(FIBERMOLD_SOURCE_DIR) / "examples" / e.folder;
    std::string text = test::read_text(source / e.design);
    for (const auto& [from, to] : e.cheap) {
      ASSERT_NE(text.find(from), std::string::npos) << e.folder << ": " << from;
      text.replace(text.find(from), from.size(), to);
    }
    int made = 0;
    for (const test::Mutant& m : test::design_mutants(text, 20, 31)) {
      test::TempDir dir;
      fs::copy(source, dir.path(), fs::copy_options::recursive);
      test::write_text(dir / "design.toml", m.text);
      if (e.design != "design.toml") fs::remove(dir / e.design);
      const test::FuzzRun r = test::fuzz_run(dir.path(), made < 2, 60, 300);
      ++codes[r.check];
      if (r.make >= 0) ++codes[100 + r.make], ++made;
      EXPECT_EQ(r.problem, "") << e.folder << ": " << m.what;
    }
    EXPECT_GE(made, 1) << e.folder << ": no mutant passed check";
  }
  for (const auto& [code, count] : codes)
    fmt::print("  {} {}: {}\n", code >= 100 ? "make" : "check", code % 100, count);
}

TEST(FuzzE2E, ABuildFolderThatIsAFileIsBadInputAndABusyOneHasItsOwnCode)
{
  test::TempDir dir;
  test::write_text(dir / "design.toml", kDesign);
  write_stl(dir / "bar.stl", bar());
  test::write_text(dir / "a-file", "x");
  const auto file = test::run_fibermold("make design.toml mesh --build-dir a-file", dir.path());
  EXPECT_EQ(file.exit_code, 2) << file.err;
  EXPECT_THAT(file.err, HasSubstr("a-file: cannot be used as the build folder: it is a file, not a folder"));
  // Another process holds the build folder's lock (flock(1) holds it while its command runs): exit 3, not 1.
  fs::create_directories(dir / "out");
  test::write_text(dir / "out" / ".lock", "");
  const auto held = test::run_command(
      fmt::format("cd '{}' && flock out/.lock -c \"'{}' make design.toml mesh --build-dir out; echo rc=\\$?\"",
                  dir.path().string(), FIBERMOLD_BINARY));
  EXPECT_THAT(held.second, HasSubstr("rc=3")) << held.second;
  EXPECT_THAT(held.second, HasSubstr("is working in out"));
}

} // namespace
} // namespace fibermold
