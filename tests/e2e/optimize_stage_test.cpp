// The optimize stage as a user runs it: a bar whose target is made by an S-shaped fiber, optimized
// from a perturbed start; its outputs, its errors, Ctrl-C, and which edits rerun it.
#include <algorithm>
#include <cmath>
#include <regex>
#include <vector>

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "test_support.hpp"

namespace fibermold {
namespace {

using ::testing::ContainsRegex;
using ::testing::HasSubstr;
namespace fs = std::filesystem;

const std::string kDesign = std::string(test::kBarDesign) + test::kBarMuscle + test::kBarTrackingCurve +
                            test::kBarTarget + "[mold]\nwall = 4.0\n";

class OptimizeE2E : public ::testing::Test {
protected:
  void SetUp() override { test::write_bar(dir_.path()); }
  void design(const std::string& extra) { test::write_text(dir_ / "design.toml", kDesign + extra); }
  test::CommandResult make(const std::string& launcher = {})
  {
    return test::run_fibermold("make design.toml optimize --build-dir build", dir_.path(), launcher);
  }
  nlohmann::json json(const std::string& file)
  {
    return nlohmann::json::parse(test::read_text(dir_ / "build" / "optimize" / file));
  }
  std::string status() { return test::run_fibermold("status design.toml --build-dir build", dir_.path()).out; }

  test::TempDir dir_;
};

TEST_F(OptimizeE2E, RecoversTheTargetAndWritesItsOutputs)
{
  design("[optimize]\nmax_iterations = 60\n");
  const auto r = make();
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto report = json("report.json");
  const auto& s = report["targets"]["s"];
  std::printf("optimize stage: RMSE %.3f → %.3f mm, max %.3f → %.3f mm, surface RMSE %.3f mm, %d iterations, %.1f s\n",
              s["start"]["rmse_mm"].get<double>(), s["rmse_mm"].get<double>(), s["start"]["max_error_mm"].get<double>(),
              s["max_error_mm"].get<double>(), s["surface_rmse_mm"].get<double>(), report["iterations"].get<int>(),
              report["seconds"]["total"].get<double>());
  EXPECT_GT(s["start"]["rmse_mm"].get<double>(), 1.0);
  EXPECT_LT(s["rmse_mm"].get<double>(), s["start"]["rmse_mm"].get<double>() / 10);
  EXPECT_LT(s["surface_rmse_mm"].get<double>(), 1.0);
  // A bar has one equilibrium: from rest it reaches the state the optimizer scored.
  EXPECT_NEAR(s["from_rest"]["rmse_mm"].get<double>(), s["rmse_mm"].get<double>(),
              0.1 * s["rmse_mm"].get<double>() + 0.01);
  const double p = s["pressure_kPa"]["m1"].get<double>();
  EXPECT_GT(p, 0);
  EXPECT_LT(p, 425);

  const auto fibers = json("fibers.json");
  ASSERT_EQ(fibers["fibers"].size(), 1u);
  const auto& m1 = fibers["fibers"][0];
  EXPECT_EQ(m1["name"], "m1");
  EXPECT_EQ(m1["points_mm"][0], nlohmann::json({0.0, 0.0, 0.0})); // end points stay fixed
  EXPECT_EQ(m1["points_mm"][3], nlohmann::json({60.0, 0.0, 0.0}));
  EXPECT_NEAR(m1["pressure_kPa"]["s"].get<double>(), p, 1e-9);
  EXPECT_GT(m1["length_mm"].get<double>(), 60);
  // The optimized route bends no tighter than the muscle takes (2 diameters: 6 mm), and the report
  // says where it bends most.
  EXPECT_EQ(report["min_bend_radius_mm"].get<double>(), 6.0);
  const auto& bend = report["bends"]["end"]["m1"];
  EXPECT_GT(bend["min_bend_radius_mm"].get<double>(), 6.0);
  EXPECT_EQ(bend["at_mm"].size(), 3u);
  EXPECT_NEAR(report["bends"]["start"]["m1"]["min_bend_radius_mm"].get<double>(), 11.4, 0.1);

  // The log follows the run each tenth of the iteration budget, with the time left once 2 s have
  // passed (this run takes about that long, more on a loaded machine).
  EXPECT_THAT(test::read_text(dir_ / "build" / "logs" / "optimize.log"),
              ContainsRegex("progress 50 %( \\(~[0-9]+ s left\\))?: iteration 30: objective"));
  const std::string history = test::read_text(dir_ / "build" / "optimize" / "history.csv");
  EXPECT_THAT(history, HasSubstr("iteration,stage,objective,distance,curvature,skin_barrier,bend_barrier,pressure_"
                                 "barrier,clearance_barrier,distance_s,"));
  EXPECT_EQ(std::count(history.begin(), history.end(), '\n'), report["iterations"].get<int>() + 1);
  EXPECT_TRUE(fs::exists(dir_ / "build" / "optimize" / "deformed-s.vtu"));

  // Edits: [mold] leaves optimize fresh; [optimize] reruns it alone; the fiber's start reruns it.
  test::write_text(dir_ / "design.toml", std::string(kDesign).replace(kDesign.find("wall = 4.0"), 10, "wall = 5.0") +
                                             "[optimize]\nmax_iterations = 60\n");
  EXPECT_THAT(status(), HasSubstr("targets   fresh\noptimize  fresh"));
  design("[optimize]\nmax_iterations = 61\n");
  EXPECT_THAT(status(), HasSubstr("targets   fresh\noptimize  stale ([optimize].max_iterations changed (60 → 61))"));
  test::write_text(dir_ / "design.toml", std::string(kDesign).replace(kDesign.find("[20, 3, -3]"), 11, "[20, 2, -3]") +
                                             "[optimize]\nmax_iterations = 61\n");
  EXPECT_THAT(status(), HasSubstr("optimize  stale"));
}

/// The target is made by the muscle at 200 kPa, and 200 kPa is all it may have: the optimizer ends
/// with the pressure against its limit, and says so, with why it stopped and how much it reached.
TEST_F(OptimizeE2E, ARunThatEndsAtThePressureLimitSaysSo)
{
  std::string text = kDesign + "[muscle]\nmax_pressure = 200\n[optimize]\nmax_iterations = 60\n";
  text.replace(text.find("pressure = 300"), 14, "pressure = 200");
  test::write_text(dir_ / "design.toml", text);
  const auto r = make();
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err,
              ContainsRegex(
                  "warning: target s: fiber m1 ends at 19[6-9]\\.[0-9] kPa, at its limit, \\[muscle\\] max_pressure = "
                  "200 kPa"));
  const auto report = json("report.json");
  const double p = report["targets"]["s"]["pressure_kPa"]["m1"].get<double>();
  EXPECT_GT(p, 0.98 * 200);
  ASSERT_GE(report["warnings"].size(), 1u);
  bool named = false;
  for (const auto& w : report["warnings"])
    named = named || w.get<std::string>().find("at its limit") != std::string::npos;
  EXPECT_TRUE(named) << report["warnings"].dump();
  // Why it stopped, and "converged" only for a vanishing gradient.
  const std::string why = report["termination"].get<std::string>();
  EXPECT_THAT(why, ContainsRegex("^(gradient tolerance met|stalled|line search failed|iteration limit)$"));
  EXPECT_EQ(report["converged"].get<bool>(), why == "gradient tolerance met");
  if (why != "gradient tolerance met") {
    EXPECT_THAT(r.err, HasSubstr("the optimizer stopped before converging (" + why));
  }
  EXPECT_GT(report["targets"]["s"]["reached_percent"].get<double>(), 90);
}

TEST_F(OptimizeE2E, SeveralStartsKeepTheRunThatEndsLowest)
{
  design("[optimize]\nmax_iterations = 12\nstarts = 3\n");
  const auto r = make();
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("start 3/3, iteration 1: objective"));
  const auto report = json("report.json");
  ASSERT_EQ(report["starts"].size(), 3u) << report["starts"].dump();
  double lowest = HUGE_VAL;
  std::vector<double> objectives;
  for (int k = 0; k < 3; ++k) {
    const auto& run = report["starts"][k];
    EXPECT_EQ(run["start"].get<int>(), k);
    EXPECT_GT(run["iterations"].get<int>(), 0);
    objectives.push_back(run["objective"].get<double>());
    lowest = std::min(lowest, objectives.back());
  }
  std::printf("starts: objectives %.6g, %.6g, %.6g\n", objectives[0], objectives[1], objectives[2]);
  // The perturbed starts are other designs: their runs end elsewhere.
  EXPECT_NE(objectives[0], objectives[1]);
  EXPECT_NE(objectives[1], objectives[2]);
  // The result is the lowest run's (the first guess at its best pressures is far above it here).
  EXPECT_EQ(report["kept"], "optimized");
  EXPECT_DOUBLE_EQ(report["objective"].get<double>(), lowest);
  // history.csv tells the runs apart.
  const std::string history = test::read_text(dir_ / "build" / "optimize" / "history.csv");
  EXPECT_THAT(history.substr(0, history.find('\n')), ::testing::EndsWith(",start"));
  for (const char* run : {",0\n", ",1\n", ",2\n"}) EXPECT_THAT(history, HasSubstr(run));
}

/// A pose of a known rotation: a straight muscle 3 mm above the bar's axis at 300 kPa turns the
/// free end by some θ about y (the targets stage measures it); a pose target asking that turn and
/// that translation of the end is met by the optimizer, started at 150 kPa, better than by the
/// straight muscle at its best pressure, and the report says how much of the turn it reached.
TEST_F(OptimizeE2E, APoseTargetOfAKnownTurnIsReachedBetterThanByTheFirstGuess)
{
  const std::string base =
      std::string(test::kBarDesign) + test::kBarTrackingCurve +
      "[[fiber]]\nname = \"m1\"\npoints = [[0, 0, 3], [20, 0, 3], [40, 0, 3], [60, 0, 3]]\n[mold]\nwall = 4.0\n";
  test::write_text(
      dir_ / "design.toml",
      base + "[[target]]\nname = \"made\"\nkind = \"fibers\"\nfibers = [{ name = \"m1\", pressure = 300 }]\n");
  auto r = test::run_fibermold("make design.toml targets --build-dir made", dir_.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto made = nlohmann::json::parse(test::read_text(dir_ / "made" / "targets" / "report.json"))["made"]["poses"];
  const auto& end = made[1]; // "centre, last point"
  ASSERT_EQ(end["place"], "centre, last point");
  const double theta = end["rotation_deg"].get<double>() * (end["rotation_axis"][1].get<double>() < 0 ? -1 : 1);
  std::printf("the muscle at 300 kPa turns the end %.2f° about y, moves it (%.2f, %.2f, %.2f) mm\n", theta,
              end["translation_mm"][0].get<double>(), end["translation_mm"][1].get<double>(),
              end["translation_mm"][2].get<double>());
  ASSERT_GT(std::abs(theta), 10);
  test::write_text(
      dir_ / "design.toml",
      base + fmt::format(
                 "[[target]]\nname = \"turn\"\nkind = \"pose\"\n"
                 "pose = [{{ box = {{ min = [59, -9, -9], max = [61, 9, 9] }}, axis = [0, 1, 0], angle_deg = {:.4f}, "
                 "about = [60, 0, 0], translation = [{:.4f}, {:.4f}, {:.4f}] }}]\n[optimize]\nmax_iterations = 60\n",
                 theta, end["translation_mm"][0].get<double>(), end["translation_mm"][1].get<double>(),
                 end["translation_mm"][2].get<double>()));
  r = make();
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto report = json("report.json");
  const auto& pose = report["targets"]["turn"]["poses"][0];
  ASSERT_EQ(pose["place"], "pose[1]");
  const double reached = pose["rotation_about_asked_axis_deg"].get<double>();
  std::printf("pose target %.2f°: the optimized robot turns %.2f° (%.1f %%) at %.1f kPa; %s after %d iterations\n",
              theta, reached, pose["rotation_reached_percent"].get<double>(),
              report["targets"]["turn"]["pressure_kPa"]["m1"].get<double>(),
              report["termination"].get<std::string>().c_str(), report["iterations"].get<int>());
  // The pose's deformation (the end held rigidly) is not the muscle's: the straight muscle at its
  // best pressure (the first guess, 259 kPa) tracks it with an RMSE of 2.04 mm; the optimizer beats
  // that, turning the end 29.3° (88 %), within the muscle's 9 mm bend radius. (With bends unlimited it
  // reached 34.0° through a bend tighter than a 3 mm muscle takes.)
  const auto& first = report["first_guess"];
  std::printf("first guess at its best pressure: objective %.4g, RMSE %.3f mm at %.1f kPa; optimized: objective %.4g, "
              "RMSE %.3f mm\n",
              first["objective"].get<double>(), first["targets"]["turn"]["rmse_mm"].get<double>(),
              first["targets"]["turn"]["pressure_kPa"]["m1"].get<double>(), report["objective"].get<double>(),
              report["targets"]["turn"]["rmse_mm"].get<double>());
  EXPECT_LE(report["objective"].get<double>(), first["objective"].get<double>());
  EXPECT_LT(report["targets"]["turn"]["rmse_mm"].get<double>(),
            0.75 * first["targets"]["turn"]["rmse_mm"].get<double>());
  EXPECT_EQ(report["kept"], "optimized");
  EXPECT_GT(report["bends"]["end"]["m1"]["min_bend_radius_mm"].get<double>(), 6.0);
  EXPECT_GT(reached / theta, 0.85);
  EXPECT_LT(reached / theta, 1.1);
  EXPECT_THAT(test::read_text(dir_ / "build" / "logs" / "optimize.log"),
              ContainsRegex("target turn: pose\\[1\\] turned -?[0-9.]+° of the"));
}

TEST_F(OptimizeE2E, AFirstGuessThatMatchesTheTargetBetterIsKeptWhateverTheBarriersSay)
{
  // A straight muscle 3.5 mm under the top skin, inside the skin barrier's band (2.5-4 mm), and a
  // target it makes itself at 300 kPa: the first guess at its best pressure meets it (RMSE < 1e-6 mm).
  // The optimizer moves the muscle inward, where the barrier costs less (0.99 -> 0.005), and pays
  // in the match (distance 0 -> 0.025): a lower objective and a robot further from the target,
  // which the stage kept until session 41 (a new user's hanging finger: RMSE 3.38 against 3.07 mm).
  // The barrier's weight 1 (its default until session 44) makes it pay.
  test::write_text(dir_ / "design.toml",
                   std::string(test::kBarDesign) + test::kBarTrackingCurve +
                       "[[fiber]]\nname = \"m1\"\npoints = [[0, 0, 4.5], [20, 0, 4.5], [40, 0, 4.5], [60, 0, 4.5]]\n"
                       "[[target]]\nname = \"made\"\nkind = \"fibers\"\nfibers = [{ name = \"m1\", pressure = 300 }]\n"
                       "[optimize]\nmax_iterations = 40\nweight_skin_barrier = 1\n");
  const auto r = make();
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto report = json("report.json");
  const auto& first = report["first_guess"];
  std::printf("first guess: objective %.4g, distance %.3g, RMSE %.3g mm; kept: %s, RMSE %.3g mm\n",
              first["objective"].get<double>(), first["distance"].get<double>(),
              first["targets"]["made"]["rmse_mm"].get<double>(), report["kept"].get<std::string>().c_str(),
              report["targets"]["made"]["rmse_mm"].get<double>());
  EXPECT_EQ(report["kept"], "first guess");
  EXPECT_LT(first["distance"].get<double>(), 1e-6);
  EXPECT_LT(report["targets"]["made"]["rmse_mm"].get<double>(), 1e-3);
  EXPECT_NEAR(report["targets"]["made"]["pressure_kPa"]["m1"].get<double>(), 300, 0.1);
  const std::string warnings = report["warnings"].dump();
  EXPECT_THAT(warnings, HasSubstr("match the targets less well than the first guess"));
  EXPECT_THAT(warnings, HasSubstr("through the skin barrier"));
  EXPECT_THAT(r.out + r.err, HasSubstr("[optimize] weight_skin_barrier)"));
  EXPECT_THAT(r.out + r.err, HasSubstr("not the targets: the first guess is kept"));
}

/// `[optimize] refine = true`: the optimized robot solved again on a mesh of half the edge length,
/// the difference at the tracking curve and the surface in the report, and a warning when it is
/// larger than the error to the target.
TEST_F(OptimizeE2E, RefineStatesTheOptimizedRobotsDiscretizationError)
{
  design("[optimize]\nmax_iterations = 60\nrefine = true\n");
  const auto r = make();
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto report = json("report.json");
  const auto& s = report["targets"]["s"];
  ASSERT_TRUE(s.contains("refined")) << s.dump();
  const auto& f = s["refined"];
  const auto mesh = nlohmann::json::parse(test::read_text(dir_ / "build" / "mesh" / "report.json"))["mesh"];
  std::printf("refine: %d → %d tets, edge %.2f mm; curves RMS %.3f max %.3f mm, surface RMS %.3f max %.3f mm (error to "
              "the target "
              "%.3f mm), %.1f s\n",
              mesh["tets"].get<int>(), f["tets"].get<int>(), f["edge_length_mm"].get<double>(),
              f["curves_rms_mm"].get<double>(), f["curves_max_mm"].get<double>(), f["surface_rms_mm"].get<double>(),
              f["surface_max_mm"].get<double>(), s["rmse_mm"].get<double>(), f["seconds"].get<double>());
  EXPECT_GT(f["tets"].get<int>(), 4 * mesh["tets"].get<int>());
  EXPECT_LT(f["edge_length_mm"].get<double>(), 0.7 * mesh["mean_edge_length_mm"].get<double>());
  EXPECT_GT(f["curves_rms_mm"].get<double>(), 0.0);
  EXPECT_LE(f["curves_rms_mm"].get<double>(), f["curves_max_mm"].get<double>());
  EXPECT_LT(f["curves_max_mm"].get<double>(), 0.5 * s["start"]["max_error_mm"].get<double>());
  bool warned = false;
  for (const auto& w : report["warnings"])
    warned = warned || w.get<std::string>().find("half the edge length") != std::string::npos;
  // Measured: 0.091 mm RMS on the finer mesh against an error of 0.027 mm to the target.
  EXPECT_GT(f["curves_rms_mm"].get<double>(), s["rmse_mm"].get<double>());
  EXPECT_TRUE(warned) << report["warnings"].dump();
  EXPECT_THAT(test::read_text(dir_ / "build" / "logs" / "optimize.log"), HasSubstr("on half the edge length"));
}

/// check and the optimize stage refuse a refined mesh over [mesh] max_tets by one rule
/// (require_refined_mesh_size): with max_tets at twice the mesh's own estimate, the mesh passes and
/// both refuse the refined one, at half the edge length, with the same message (the stage used
/// 8 × the mesh's tets, which check did not).
TEST_F(OptimizeE2E, CheckAndTheStageRefuseATooLargeRefinedMeshAlike)
{
  design("[optimize]\nmax_iterations = 3\n");
  ASSERT_EQ(test::run_fibermold("make design.toml mesh --build-dir build", dir_.path()).exit_code, 0);
  const double estimate = nlohmann::json::parse(
      test::read_text(dir_ / "build" / "mesh" / "report.json"))["mesh"]["sizing"]["estimated_tets"];
  std::string text = kDesign + "[optimize]\nmax_iterations = 3\nrefine = true\n";
  text.replace(text.find("edge_length = 8"), 15, fmt::format("edge_length = 8\nmax_tets = {:.0f}", 2 * estimate));
  test::write_text(dir_ / "design.toml", text);
  const auto checked = test::run_fibermold("check design.toml", dir_.path());
  const auto made = make();
  EXPECT_EQ(checked.exit_code, 2) << checked.out << checked.err;
  EXPECT_EQ(made.exit_code, 2) << made.out << made.err;
  const std::regex refusal("\\[optimize\\]\\.refine: [^\\n]*would make about [0-9.e+]+ tets[^\\n]*");
  std::smatch in_check, in_make;
  ASSERT_TRUE(std::regex_search(checked.err, in_check, refusal)) << checked.err;
  ASSERT_TRUE(std::regex_search(made.err, in_make, refusal)) << made.err;
  EXPECT_EQ(in_check.str(), in_make.str());
  std::printf("refused alike at max_tets = %.0f: %s\n", 2 * estimate, in_check.str().c_str());
}

/// One rule for how far a fiber stays from the skin (stages/skin_distance.hpp): where the groove
/// needs more than radius + clearance (a 2 mm muscle, clearance 0.5 mm, groove_clearance 0.3 mm
/// and min_silicone 0.5 mm beside it: 1 + 0.3 + 0.5 = 1.8 mm against 1.5), check refuses a route
/// 1.52 mm from the skin, naming the groove; one 1.85 mm from it passes check and every stage
/// through the molds (the silicone beside its groove included).
TEST_F(OptimizeE2E, CheckOptimizeCollideAndMoldsKeepFibersFromTheSkinByOneRule)
{
  const std::string route = "points = [[0, 0, 0], [20, 3, -3], [40, -3, 2], [60, 0, 0]]";
  const auto at = [&](double y) {
    std::string text =
        kDesign + "[muscle]\ndiameter = 2.0\n[collide]\nclearance = 0.5\n[optimize]\nmax_iterations = 3\n";
    text.replace(text.find(route), route.size(),
                 fmt::format("points = [[0, {0}, 0], [20, {0}, 0], [40, {0}, 0], [60, {0}, 0]]", y));
    text.replace(text.find("wall = 4.0"), 10, "wall = 4.0\ngroove_clearance = 0.3\nvoxel = 0.5\nkeys = 2");
    test::write_text(dir_ / "design.toml", text);
  };
  at(8 - 1.52);
  const auto refused = test::run_fibermold("check design.toml", dir_.path());
  EXPECT_EQ(refused.exit_code, 2) << refused.out << refused.err;
  EXPECT_THAT(refused.err, HasSubstr("[fiber.m1].points: the starting route passes 1.520 mm from the skin"));
  EXPECT_THAT(refused.err,
              HasSubstr("more than 1.800 mm inside ([muscle] diameter/2 = 1 mm + [mold] groove_clearance = 0.3 mm + "
                        "[mold] min_silicone = 0.5 mm, what the groove needs): move the route more than 0.280 mm"));
  at(8 - 1.85);
  const auto passed = test::run_fibermold("check design.toml", dir_.path());
  ASSERT_EQ(passed.exit_code, 0) << passed.err;
  const auto made = test::run_fibermold("make design.toml molds --build-dir build", dir_.path());
  EXPECT_EQ(made.exit_code, 0) << made.err;
}

/// A 3 mm muscle routed 1.5 mm from the bar's skin (y = 6.5 of 8 mm): `check` refuses it, naming
/// the fiber, the distance, the rule and the fix, before any stage runs.
TEST_F(OptimizeE2E, AFiberTooNearTheSkinIsRefusedByCheckWithTheFix)
{
  std::string text = kDesign;
  const std::string route = "points = [[0, 0, 0], [20, 3, -3], [40, -3, 2], [60, 0, 0]]";
  text.replace(text.find(route), route.size(), "points = [[0, 6.5, 0], [20, 6.5, 0], [40, 6.5, 0], [60, 6.5, 0]]");
  test::write_text(dir_ / "design.toml", text);
  const auto checked = test::run_fibermold("check design.toml", dir_.path());
  EXPECT_EQ(checked.exit_code, 2) << checked.err;
  EXPECT_THAT(checked.err,
              ContainsRegex(
                  "design.toml:[0-9]+:[0-9]+: \\[fiber.m1\\]\\.points: the starting route passes 1\\.[0-9]{3} mm from "
                  "the skin at \\([0-9.]+, 6\\.[0-9], -?[0-9.]+\\) mm, where the optimizer keeps a fiber's "
                  "centre line more than 2\\.500 mm inside \\(\\[muscle\\] diameter/2 = 1\\.5 mm \\+ "
                  "\\[collide\\] clearance = 1 mm\\): move the route more than 1\\.000 mm inward there"));
  EXPECT_FALSE(fs::exists(dir_ / "build"));
}

/// A route leaving the bar's held end face 80° off its normal, along the face: check refuses it where it
/// runs along the skin, with the ramp it must clear; leaving square to the face it passes.
TEST_F(OptimizeE2E, AFiberLeavingTheBodyAlongTheSkinIsRefusedByCheck)
{
  std::string text = kDesign;
  const std::string route = "points = [[0, 0, 0], [20, 3, -3], [40, -3, 2], [60, 0, 0]]";
  text.replace(text.find(route), route.size(),
               "points = [[0, -4, 0], [20, 0, 0], [40, 0, 0], [60, 0, 0]]\n"
               "tangents = [[3.5, 20, 0], [20, 0, 0], [20, 0, 0], [20, 0, 0]]");
  test::write_text(dir_ / "design.toml", text);
  const auto along = test::run_fibermold("check design.toml", dir_.path());
  EXPECT_EQ(along.exit_code, 2) << along.err;
  EXPECT_THAT(along.err,
              ContainsRegex("\\[fiber.m1\\]\\.points: the starting route leaves the body along the skin, not into "
                            "it: at \\(0\\.[0-9], -3\\.[0-9], 0\\.0\\) mm, 0\\.[0-9] mm from its "
                            "end on the skin, it is 0\\.[0-9]{3} mm from the skin, where a route is kept "
                            "more than 0\\.[0-9]{3} mm inside \\(rising to 2\\.500 mm at 8\\.0 mm from the "
                            "end: a route leaving a flat face within 72° of its normal clears it\\)"));
  text.replace(text.find("[[3.5, 20, 0]"), 13, "[[20, 3.5, 0]");
  test::write_text(dir_ / "design.toml", text);
  const auto square = test::run_fibermold("check design.toml", dir_.path());
  EXPECT_EQ(square.exit_code, 0) << square.err;
}

/// A route with a 4 mm bump over 10 mm bends with a 0.49 mm radius: check refuses it against the
/// default [muscle] min_bend_radius (2 diameters, 6 mm), naming the fiber, the radius and where;
/// so does the optimize stage with the optimizer off (the molds would cast it); a muscle declared
/// to bend that tight passes.
TEST_F(OptimizeE2E, ARouteBentTighterThanTheMuscleTakesIsRefused)
{
  std::string text = kDesign;
  const std::string route = "points = [[0, 0, 0], [20, 3, -3], [40, -3, 2], [60, 0, 0]]";
  text.replace(text.find(route), route.size(), "points = [[0, 0, 0], [20, 0, 0], [25, 4, 0], [30, 0, 0], [60, 0, 0]]");
  test::write_text(dir_ / "design.toml", text);
  const auto checked = test::run_fibermold("check design.toml", dir_.path());
  EXPECT_EQ(checked.exit_code, 2) << checked.err;
  EXPECT_THAT(
      checked.err,
      ContainsRegex("design.toml:[0-9]+:[0-9]+: \\[fiber.m1\\]\\.points: the starting route bends with a radius of "
                    "0\\.[0-9]{2} "
                    "mm at \\((2[0-9])\\.[0-9], [0-9.]+, 0\\.0\\) mm, [0-9.]+ mm along it, tighter than \\[muscle\\] "
                    "min_bend_radius = 6 mm"));
  test::write_text(dir_ / "design.toml", text + "[optimize]\nenabled = false\n");
  EXPECT_EQ(make().exit_code, 2);
  test::write_text(dir_ / "design.toml", text + "[muscle]\nmin_bend_radius = 0.4\n");
  EXPECT_EQ(test::run_fibermold("check design.toml", dir_.path()).exit_code, 0);
}

TEST_F(OptimizeE2E, DisabledPassesTheFibersThrough)
{
  design("[optimize]\nenabled = false\n");
  ASSERT_EQ(make().exit_code, 0);
  const auto fibers = json("fibers.json");
  EXPECT_EQ(fibers["optimized"], false);
  EXPECT_EQ(fibers["fibers"][0]["points_mm"][1], nlohmann::json({20.0, 3.0, -3.0}));
}

TEST_F(OptimizeE2E, BadInputsAreNamed)
{
  design("[optimize]\nstrategy = \"sequential\"\n[[fiber]]\nname = \"m2\"\npoints = [[0, 2, 2], [60, 2, 2]]\n");
  auto r = make();
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(
      r.err,
      HasSubstr("[optimize].strategy: sequential drives one fiber per target, in order: 2 fiber(s) for 1 target(s)"));

  design("[[tracking_curve]]\nname = \"out\"\npoints = [[0, 0, 0], [60, 0, 12]]\n");
  r = make();
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err,
              ::testing::ContainsRegex(
                  "design\\.toml:[0-9]+:[0-9]+: \\[tracking_curve\\.out\\]\\.points\\[2\\]: the curve leaves the "
                  "body at"));
  // Which of its points to move: the second; the first, on the skin, is in.
  EXPECT_THAT(r.err, HasSubstr("of its 2 points, point 2 (60.0, 0.0, 12.0) mm lies outside: move it inside the body"));
  // Unnamed, it is found by its default name, at its line all the same.
  design("[[tracking_curve]]\npoints = [[0, 0, 0], [60, 0, 12]]\n");
  r = make();
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err,
              ::testing::ContainsRegex(
                  "design\\.toml:[0-9]+:[0-9]+: \\[tracking_curve\\.curve[0-9]\\]\\.points\\[2\\]: the curve leaves "
                  "the body at"));
}

TEST_F(OptimizeE2E, InterruptKeepsTheBestDesignSoFar)
{
  // Ctrl-C once the stage's log shows its fifth iteration: a fixed delay raced the optimization,
  // which got faster each session (on 5 mm edges it now ends in about 10 s).
  design("[optimize]\nmax_iterations = 100000\nrelative_tolerance = 1e-15\ngradient_tolerance = 1e-15\n");
  ASSERT_EQ(test::run_fibermold("make design.toml targets --build-dir build", dir_.path()).exit_code, 0);
  const std::string interrupt_after_five_iterations =
      "bash -c '\"$@\" & pid=$!; for i in $(seq 1200); do grep -qs \"iteration 5:\" build/logs/optimize.log && break; "
      "sleep 0.05; done; kill -INT $pid; wait $pid' interrupt";
  const auto r = make(interrupt_after_five_iterations);
  EXPECT_EQ(r.exit_code, 130) << r.err;
  EXPECT_THAT(r.err, HasSubstr("the best design so far"));
  EXPECT_THAT(r.err, ContainsRegex("interrupted after ([5-9]|[1-9][0-9]+) iterations"));
  const auto kept = nlohmann::json::parse(test::read_text(dir_ / "build" / "optimize.interrupted" / "fibers.json"));
  EXPECT_EQ(kept["fibers"][0]["name"], "m1");
  EXPECT_FALSE(fs::exists(dir_ / "build" / "optimize" / "fibers.json")) << "no output that looks complete";
  EXPECT_THAT(status(), HasSubstr("optimize  stale"));
}

} // namespace
} // namespace fibermold
