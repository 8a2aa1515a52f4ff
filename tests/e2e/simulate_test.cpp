// `fibermold simulate` as a user runs it: a small bar with one muscle.
#include <cstdio>
#include <regex>

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "export/stl_writer.hpp"
#include "primitives.hpp"
#include "test_support.hpp"

namespace fibermold {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;
namespace fs = std::filesystem;

class SimulateE2E : public ::testing::Test {
protected:
  void SetUp() override
  {
    write_stl(dir_ / "bar.stl", test::box({0, -0.008, -0.008}, {0.06, 0.008, 0.008}, Eigen::Vector3i(10, 3, 3)));
  }
  /// A design with `fixed` as its [[fixed]] table(s) and `fiber` as the fiber's points.
  void design(const std::string& fixed = "[[fixed]]\nbox = { min = [-1, -9, -9], max = [0.5, 9, 9] }\n",
              const std::string& fiber = "[[0, 0, 0], [30, 2, 0], [60, 0, 0]]")
  {
    test::write_text(dir_ / "design.toml",
                     "[design]\nname = \"bar\"\nsurface = \"bar.stl\"\n[mesh]\nedge_length = 6\n"
                     "[material]\ngravity = [0, 0, 0]\n" +
                         fixed + "[[fiber]]\nname = \"m1\"\npoints = " + fiber +
                         "\n[[target]]\nname = \"pull\"\nkind = \"forces\"\n"
                         "load = [{ box = { min = [59, -9, -9], max = [61, 9, 9] }, force = [0, 0, -0.05] }]\n");
  }
  test::CommandResult simulate(const std::string& args)
  {
    return test::run_fibermold("simulate design.toml --build-dir build " + args, dir_.path());
  }

  test::TempDir dir_;
  test::CommandResult r_;
};

TEST_F(SimulateE2E, PressurizedMuscleDeformsTheBarAndWritesTheVtu)
{
  design();
  const auto r = simulate("--pressure m1=300");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("simulate pressures-m1-300kPa: max displacement"));
  EXPECT_THAT(r.out, HasSubstr("Newton"));
  const std::string vtu = test::read_text(dir_ / "build" / "simulate" / "deformed-pressures-m1-300kPa.vtu");
  EXPECT_THAT(vtu, HasSubstr("Name=\"displacement_mm\""));
  EXPECT_THAT(vtu, HasSubstr("Name=\"von_mises_kPa\""));
  const double max_mm = std::stod(r.out.substr(r.out.find("max displacement") + 17));
  EXPECT_GT(max_mm, 0.5); // a 300 kPa muscle in a 60 mm EcoFlex bar moves it by millimetres
  EXPECT_LT(max_mm, 30);
}

/// Given pressures, simulate says where the tracking curves' ends go, as for a target as built: the
/// bar's axis's end moves by nearly the largest displacement (a corner's) and turns about z, toward
/// the muscle's side; its held first point is not listed. (The line wraps.)
TEST_F(SimulateE2E, APressuredRunSaysWhereTheTrackingCurvesEndsGo)
{
  design();
  test::write_text(dir_ / "design.toml", test::read_text(dir_ / "design.toml") +
                                             "[[tracking_curve]]\nname = \"axis\"\npoints = [[0, 0, 0], [60, 0, 0]]\n");
  const auto r = simulate("--pressure m1=300");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const double max_mm = std::stod(r.out.substr(r.out.find("max displacement") + 17));
  std::smatch m;
  const std::regex line(
      R"(axis, last point \(at \(60\.0, 0\.0, 0\.0\) mm at rest\): moves ([0-9.]+) mm \(([-0-9.]+), )"
      R"(([-0-9.]+), ([-0-9.]+)\) and turns\s+([0-9.]+)° about \(([-0-9.]+), ([-0-9.]+), ([-0-9.]+)\))");
  ASSERT_TRUE(std::regex_search(r.out, m, line)) << r.out;
  std::printf("tip moves %s mm, turns %s° about (%s, %s, %s); max displacement %.3f mm\n", m[1].str().c_str(),
              m[5].str().c_str(), m[6].str().c_str(), m[7].str().c_str(), m[8].str().c_str(), max_mm);
  EXPECT_GT(std::stod(m[1]), 0.8 * max_mm);
  EXPECT_LE(std::stod(m[1]), max_mm + 0.05);
  EXPECT_GT(std::stod(m[3]), 0.5);  // toward +y, the muscle's side
  EXPECT_GT(std::stod(m[5]), 1.0);  // a turn of degrees
  EXPECT_GT(std::stod(m[8]), 0.95); // about +z
  EXPECT_THAT(r.out, Not(HasSubstr("axis, first point")));
}

/// The cast robot holds every muscle: one not given a pressure is in the body at 0 kPa, and stiffens
/// it (a new user's finger sagged 66.9 mm with its muscle left out, 57.7 mm with it at rest).
TEST_F(SimulateE2E, AFiberGivenNoPressureIsInTheBodyAtRest)
{
  design();
  std::string text = test::read_text(dir_ / "design.toml");
  text += "[[fiber]]\nname = \"m2\"\npoints = [[0, 0, -4], [60, 0, -4]]\n";
  text.replace(text.find("gravity = [0, 0, 0]"), 19, "gravity = [0, 0, -9.81]");
  test::write_text(dir_ / "design.toml", text);
  const auto max_mm = [](const std::string& out) { return std::stod(out.substr(out.find("max displacement") + 17)); };

  const auto one = simulate("--pressure m1=300");
  ASSERT_EQ(one.exit_code, 0) << one.err;
  EXPECT_THAT(one.out, HasSubstr("muscles: m1 300 kPa, m2 0 kPa"));
  const std::string vtu = test::read_text(dir_ / "build" / "simulate" / "deformed-pressures-m1-300kPa.vtu");
  const auto both = simulate("--pressure m1=300 --pressure m2=0");
  ASSERT_EQ(both.exit_code, 0) << both.err;
  // Each run at other pressures writes a file of its own, named by the pressures given.
  EXPECT_EQ(test::read_text(dir_ / "build" / "simulate" / "deformed-pressures-m1-300kPa-m2-0kPa.vtu"), vtu);

  // Neither flag: the robot unactuated, both muscles at rest, under its weight.
  const auto rest = simulate("");
  ASSERT_EQ(rest.exit_code, 0) << rest.err;
  EXPECT_THAT(rest.out, HasSubstr("simulate unactuated: max displacement"));
  EXPECT_THAT(rest.out, HasSubstr("muscles: m1 0 kPa, m2 0 kPa"));
  EXPECT_TRUE(fs::exists(dir_ / "build" / "simulate" / "deformed-unactuated.vtu"));
  // The muscles at rest stiffen the sagging bar: a body without them sags further.
  test::write_text(dir_ / "design.toml",
                   text.substr(0, text.find("[[fiber]]")) +
                       text.substr(text.find("[[target]]"), text.rfind("[[fiber]]") - text.find("[[target]]")));
  const auto bare = simulate("");
  ASSERT_EQ(bare.exit_code, 0) << bare.err;
  EXPECT_THAT(bare.out, HasSubstr("no muscle: the body under its weight and its held regions"));
  std::printf("sag with the muscles at rest %.3f mm, without them %.3f mm\n", max_mm(rest.out), max_mm(bare.out));
  EXPECT_GT(max_mm(bare.out), 1.02 * max_mm(rest.out)) << rest.out << bare.out;
}

/// `--refine` solves again at half the edge length and says how far the figures are from
/// converged. On a coarser mesh the difference is larger: the estimate follows the mesh.
TEST_F(SimulateE2E, RefineReportsTheDiscretizationErrorAndItShrinksWithTheMesh)
{
  std::string said; // the last run's output
  const auto refined = [&](double edge) {
    design();
    const std::string text = test::read_text(dir_ / "design.toml");
    test::write_text(dir_ / "design.toml",
                     std::regex_replace(text, std::regex("edge_length = 6"), fmt::format("edge_length = {}", edge)));
    const auto r = simulate("--target pull --refine");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    std::smatch m;
    EXPECT_TRUE(std::regex_search(r.out, m, std::regex(R"(surface max ([0-9.]+) mm, RMS ([0-9.]+) mm)"))) << r.out;
    EXPECT_TRUE(fs::exists(dir_ / "build" / "simulate" / "deformed-pull-refined.vtu"));
    const double surface = m.size() > 1 ? std::stod(m[1]) : 0.0;
    // Warned of exactly where the surface moves more than 5 % of the largest displacement.
    const double largest = std::stod(r.out.substr(r.out.find("max displacement") + 17));
    std::printf("edge %g mm: surface moves %.3f mm of %.3f mm\n", edge, surface, largest);
    said = r.out;
    EXPECT_EQ(r.out.find("the design's mesh is coarse for this deformation") != std::string::npos,
              surface > 0.05 * largest)
        << r.out;
    return surface;
  };
  const double coarse = refined(10);
  EXPECT_THAT(said, HasSubstr("warning: the surface moves 8.6 % of the largest displacement")); // the warned case
  const double fine = refined(6);
  EXPECT_THAT(said, Not(HasSubstr("coarse for this deformation")));
  std::printf("bar under a tip load: refinement changes the surface by up to %.3f mm at 10 mm edges, %.3f mm at 6 mm\n",
              coarse, fine);
  EXPECT_GT(coarse, 0);
  EXPECT_GT(fine, 0);
  EXPECT_LT(fine, coarse);
}

TEST_F(SimulateE2E, TargetLoads)
{
  design();
  const auto r = simulate("--target pull");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("simulate pull: max displacement"));
  EXPECT_TRUE(fs::exists(dir_ / "build" / "simulate" / "deformed-pull.vtu"));
}

TEST_F(SimulateE2E, PressureOutOfRange)
{
  design();
  const auto r = simulate("--pressure m1=500");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("500 kPa for m1 is outside [0, 425] kPa"));
  const auto unknown = simulate("--pressure m9=100");
  EXPECT_EQ(unknown.exit_code, 2);
  EXPECT_THAT(unknown.err, HasSubstr("no [[fiber]] named \"m9\" (the design has m1)"));
  EXPECT_EQ(simulate("--pressure m1").exit_code, 2);
  // A unit after the number is refused, not dropped: "300Pa" ran at 300 kPa, "0.3MPa" at 0.3 kPa.
  // Nor is a hexadecimal number, or infinity.
  for (const char* typed :
       {"m1=300Pa", "m1=0.3MPa", "m1=2bar", "m1=30psi", "m1=100kPa", "m1=1e2x", "m1=0x12c", "m1=0x1p8", "m1=inf"}) {
    const auto unit = simulate(std::string("--pressure ") + typed);
    EXPECT_EQ(unit.exit_code, 2) << typed;
    EXPECT_THAT(unit.err, HasSubstr(std::string("'") + typed +
                                    "': expected FIBER=kPa, the pressure a number in kPa without a unit"));
  }
}

TEST_F(SimulateE2E, FiberOutsideTheBody)
{
  design("[[fixed]]\nbox = { min = [-1, -9, -9], max = [0.5, 9, 9] }\n", "[[0, 0, 0], [30, 20, 0], [60, 0, 0]]");
  const auto r = simulate("--pressure m1=100");
  EXPECT_EQ(r.exit_code, 2);
  // At the point to move: line 12 is `points = [[0, 0, 0], [30, 20, 0], ...`, its second point at column 22.
  EXPECT_THAT(r.err, HasSubstr("design.toml:12:22: [fiber.m1].points[2]: the fiber leaves the body at ("));
  // Which of the points the user gave to move, counted as they count them.
  EXPECT_THAT(r.err, HasSubstr("of its 3 points, point 2 (30.0, 20.0, 0.0) mm lies outside: move it inside the body"));
  // All points inside (the bar is ±8 mm in z), the middle one 3 mm from the skin (more than the 2.5
  // mm a fiber keeps), the curve through them bulging out: its first span rises to z = 5 + 30 · 4/27
  // = 9.4 mm.
  design("[[fixed]]\nbox = { min = [-1, -9, -9], max = [0.5, 9, 9] }\n",
         "[[0, 0, 5], [30, 0, 5], [60, 0, 5]]\ntangents = [[30, 0, 30], [30, 0, 0], [30, 0, -30]]");
  const auto bulge = simulate("--pressure m1=100");
  EXPECT_EQ(bulge.exit_code, 2);
  EXPECT_THAT(bulge.err, HasSubstr("between its points, which all lie inside: the curve through them bulges out"));
  // A route drawn along the skin (points 2 and 3 on the top face, z = 8 mm): the curve leaves the
  // body between them because they lie on the skin, which the message says, not a bulge. Its ends
  // (on the end faces, where a muscle leaves the body) are not named.
  design("[[fixed]]\nbox = { min = [-1, -9, -9], max = [0.5, 9, 9] }\n", "[[0, 0, 4], [30, 0, 8], [60, 0, 8]]");
  const auto skin = simulate("--pressure m1=100");
  EXPECT_EQ(skin.exit_code, 2);
  EXPECT_THAT(skin.err, HasSubstr("between its points, which lie inside but too near the skin: point 2 (30.0, 0.0, "
                                  "8.0) mm is 0.000 mm from it; a curve through points on or near the skin"));
  EXPECT_THAT(skin.err, HasSubstr("a fiber's centre line must stay more than"));
  EXPECT_THAT(skin.err, Not(HasSubstr("bulges out")));
}

TEST_F(SimulateE2E, ATargetsOwnRouteOutsideTheBodyIsPlacedAtTheFiberNotAtTheDrawnPoints)
{
  // The [[fiber]] as drawn is inside; the target's own route for it is not. The drawn points are
  // not what to move, so the error names the fiber, as for a route the optimizer or collide moved.
  design();
  test::write_text(dir_ / "design.toml",
                   test::read_text(dir_ / "design.toml") +
                       "[[target]]\nname = \"made\"\nkind = \"fibers\"\n"
                       "fibers = [{ name = \"m1\", pressure = 100, points = [[0, 0, 0], [30, 20, 0], [60, 0, 0]] }]\n");
  const auto r = simulate("--target made");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("[fiber.m1]: the fiber leaves the body at ("));
  EXPECT_THAT(r.err, HasSubstr("point 2 (30.0, 20.0, 0.0) mm lies outside"));
}

TEST_F(SimulateE2E, FixedRegionThatCatchesNoNode)
{
  design("[[fixed]]\nname = \"clamp\"\nbox = { min = [100, -9, -9], max = [110, 9, 9] }\n");
  const auto r = simulate("--pressure m1=100");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("[fixed.clamp]: holds no node of the mesh"));
}

TEST_F(SimulateE2E, BadLoadsAndFibersAreRefused)
{
  const std::string fixed = "[[fixed]]\nbox = { min = [-1, -9, -9], max = [0.5, 9, 9] }\n";
  design(fixed, "[[30, 0, 0], [30, 0, 0]]");
  auto r = simulate("--pressure m1=100");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("design.toml:12:10: [fiber.m1].points: the fiber has no length"));

  design();
  r = simulate("--pressure m1=100 --pressure m1=200");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("m1 is given twice"));

  std::string text = test::read_text(dir_ / "design.toml");
  const std::string load = "load = [{ box = { min = [59, -9, -9], max = [61, 9, 9] }, force = [0, 0, -0.05] }]";
  test::write_text(
      dir_ / "design.toml",
      std::string(text).replace(text.find(load), load.size(), "load = [{ vertices = [5], torque = [0.001, 0, 0] }]"));
  r = simulate("--target pull");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("a torque needs at least 3 nodes that are not on one line; the region holds 1 node(s)"));

  test::write_text(dir_ / "design.toml",
                   std::string(text).replace(text.find(load), load.size(),
                                             "load = [{ point = [60, 0, 40], force = [0, 0, -0.01] }]"));
  r = simulate("--target pull");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("the point (60.0, 0.0, 40.0) mm lies outside the body"));
}

TEST_F(SimulateE2E, LoadsDoNotDependOnDensity)
{
  design();
  std::string text = test::read_text(dir_ / "design.toml");
  test::write_text(dir_ / "design.toml",
                   text.replace(text.find("gravity = [0, 0, 0]"), 19, "gravity = [0, 0, 0]\ndensity = 0"));
  const auto r = simulate("--target pull");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("simulate pull: max displacement"));
}

TEST_F(SimulateE2E, FreeBodyIsRefused)
{
  design("");
  const auto r = simulate("--target pull");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("the body is held nowhere"));
  // By check too, before any stage runs (it said "ok ... 0 fixed region(s)" until session 41).
  test::write_text(dir_ / "design.toml", test::read_text(dir_ / "design.toml") +
                                             "[[tracking_curve]]\nname = \"axis\"\npoints = [[0, 0, 0], [60, 0, 0]]\n");
  const auto checked = test::run_fibermold("check design.toml", dir_.path());
  EXPECT_EQ(checked.exit_code, 2);
  EXPECT_THAT(checked.err, HasSubstr("[[fixed]]: the body is held nowhere: add a [[fixed]] region"));
}

/// `--as-built` takes the routes and a target's pressures from collide/fibers.json, the routing the
/// molds were carved for, and not the design's first guess: the bar with the file's route at the
/// file's pressure is exactly the bar whose design has that route, pressurized so.
TEST_F(SimulateE2E, AsBuiltSimulatesTheRoutesAndPressuresTheMoldsWereMadeFor)
{
  const std::string route = "[[0, 0, 0], [30, -2, 1], [60, 0, 0]]", tangents = "[[30, 0, 0], [30, -1, 0], [30, 0, 0]]";
  design();
  r_ = simulate("--as-built --target pull");
  EXPECT_EQ(r_.exit_code, 2);
  EXPECT_THAT(r_.err, HasSubstr("collide/fibers.json: --as-built: does not exist. --as-built reads the routes the "
                                "molds were made for from the build folder they were made in: give --build-dir the "
                                "folder bar's molds were made in"));
  fs::create_directories(dir_ / "build" / "collide");
  const auto fibers = [&](const std::string& name, const std::string& target, const std::string& kpa = "150.0") {
    test::write_text(dir_ / "build" / "collide" / "fibers.json",
                     "{\"optimized\": true, \"fibers\": [{\"name\": \"" + name + "\", \"points_mm\": " + route +
                         ", \"tangents_mm\": " + tangents + ", \"length_mm\": 60.2, \"pressure_kPa\": {\"" + target +
                         "\": " + kpa + "}}]}");
  };
  fibers("m1", "pull");
  const auto as_built = simulate("--as-built --target pull");
  ASSERT_EQ(as_built.exit_code, 0) << as_built.err;
  EXPECT_THAT(as_built.out, HasSubstr("simulate pull-as-built: max displacement"));
  EXPECT_THAT(as_built.out, HasSubstr("as built: the routes of build/collide/fibers.json, at target pull's pressures "
                                      "there (m1 150 kPa); [material] youngs_modulus 86400 Pa"));
  // Where the target's load region went, as README.txt's lines to compare give it.
  EXPECT_THAT(as_built.out, HasSubstr("load[1] (at (60.0, "));
  const std::string vtu = test::read_text(dir_ / "build" / "simulate" / "deformed-pull-as-built.vtu");
  const auto with_pressure = simulate("--as-built --pressure m1=150");
  ASSERT_EQ(with_pressure.exit_code, 0) << with_pressure.err;
  EXPECT_EQ(test::read_text(dir_ / "build" / "simulate" / "deformed-pressures-m1-150kPa-as-built.vtu"), vtu);
  // The target's regions at other pressures (what README.txt's full turn names): the same robot at the
  // file's 150 kPa, another at 200, each in its own file; without --as-built, refused.
  const auto given = simulate("--as-built --target pull --pressure m1=150");
  ASSERT_EQ(given.exit_code, 0) << given.err;
  EXPECT_THAT(given.out, HasSubstr("target pull's regions at the pressures given (m1 150 kPa); [material]"));
  EXPECT_EQ(test::read_text(dir_ / "build" / "simulate" / "deformed-pull-m1-150kPa-as-built.vtu"), vtu);
  const auto higher = simulate("--as-built --target pull --pressure m1=200");
  ASSERT_EQ(higher.exit_code, 0) << higher.err;
  EXPECT_THAT(higher.out, HasSubstr("load[1] (at (60.0, "));
  const auto moved_mm = [](const std::string& out) {
    const auto at = out.find("load[1]");
    return std::stod(out.substr(out.find("moves ", at) + 6));
  };
  EXPECT_GT(moved_mm(higher.out), moved_mm(as_built.out) + 0.1);
  EXPECT_THAT(simulate("--target pull --pressure m1=150").err,
              HasSubstr("give either --target or --pressure, not both (with --as-built, both"));

  // The design given that route, simulated as a design is.
  std::string text = test::read_text(dir_ / "design.toml");
  const std::string guess = "points = [[0, 0, 0], [30, 2, 0], [60, 0, 0]]";
  test::write_text(dir_ / "design.toml",
                   text.replace(text.find(guess), guess.size(), "points = " + route + "\ntangents = " + tangents));
  const auto designed = simulate("--pressure m1=150");
  ASSERT_EQ(designed.exit_code, 0) << designed.err;
  EXPECT_EQ(test::read_text(dir_ / "build" / "simulate" / "deformed-pressures-m1-150kPa.vtu"), vtu);
  const auto max_mm = [](const std::string& out) { return std::stod(out.substr(out.find("max displacement") + 17)); };
  EXPECT_EQ(max_mm(designed.out), max_mm(as_built.out));
  // …and not the first guess's.
  design();
  const auto first_guess = simulate("--pressure m1=150");
  ASSERT_EQ(first_guess.exit_code, 0) << first_guess.err;
  EXPECT_GT(std::abs(max_mm(first_guess.out) - max_mm(as_built.out)), 0.01);

  // A file for another design, or none of the target's pressures, or not a fibers file: exit 2, and why.
  fibers("m2", "pull");
  r_ = simulate("--as-built --pressure m1=150");
  EXPECT_EQ(r_.exit_code, 2);
  EXPECT_THAT(r_.err, HasSubstr("holds fiber \"m2\", which the design has not: its molds were made for another "
                                "design"));
  fibers("m1", "pull", "500.0");
  r_ = simulate("--as-built --target pull");
  EXPECT_EQ(r_.exit_code, 2);
  EXPECT_THAT(r_.err, HasSubstr("fiber m1: target pull's pressure 500 kPa is outside [0, 425] kPa"));
  fibers("m1", "lift");
  r_ = simulate("--as-built --target pull");
  EXPECT_EQ(r_.exit_code, 2);
  EXPECT_THAT(r_.err, HasSubstr("holds no pressures for target \"pull\" (it has lift): its molds were made for "
                                "another design"));
  test::write_text(dir_ / "build" / "collide" / "fibers.json", "{\"fibers\": 3}");
  r_ = simulate("--as-built --target pull");
  EXPECT_EQ(r_.exit_code, 2);
  EXPECT_THAT(r_.err, HasSubstr("not a fibers file"));
  EXPECT_EQ(r_.err.find("fibers.json: not a fibers file"), std::string::npos) << r_.err; // the path said once
  r_ = simulate("--as-built");
  EXPECT_EQ(r_.exit_code, 2);
  EXPECT_THAT(r_.err, HasSubstr("--as-built: give --target NAME"));
  r_ = simulate("--as-built --target plul"); // a typo: the targets there are
  EXPECT_EQ(r_.exit_code, 2);
  EXPECT_THAT(r_.err, HasSubstr("--target: no [[target]] named \"plul\" (the design has pull)"));
  // Another body's design on this build folder is refused before anything is meshed there.
  fibers("m1", "pull");
  const std::string mesh_before = test::read_text(dir_ / "build" / "mesh" / "body.tetmesh");
  write_stl(dir_ / "other.stl", test::box({0, -0.008, -0.008}, {0.07, 0.008, 0.008}, Eigen::Vector3i(10, 3, 3)));
  text = test::read_text(dir_ / "design.toml");
  test::write_text(dir_ / "design.toml", text.replace(text.find("bar.stl"), 7, "other.stl"));
  r_ = simulate("--as-built --target pull");
  EXPECT_EQ(r_.exit_code, 2);
  EXPECT_THAT(r_.err, HasSubstr("this build folder was made from "));
  EXPECT_THAT(r_.err, HasSubstr("bar.stl, not from bar's surface "));
  EXPECT_EQ(test::read_text(dir_ / "build" / "mesh" / "body.tetmesh"), mesh_before);
}

} // namespace
} // namespace fibermold
