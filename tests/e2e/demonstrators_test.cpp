// The paper's demonstrators (examples/, section VIII) as a user runs them, on coarser meshes and
// shorter optimizations than the examples so that CI can afford them: each runs `fibermold make`
// to the end (the cantilever, which has no muscle, `simulate`; the tip-only tentacle to collide),
// every mold part passes its checks, and the target errors are held to 1.5× the paper's where it
// gives them and to ours where it does not (the walking robot).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "fill_checks.hpp"
#include "mesh/surface_distance.hpp"
#include "mesh/tet_mesh.hpp"
#include "sim/hermite_spline.hpp"
#include "test_support.hpp"

namespace fibermold {
namespace {

using ::testing::HasSubstr;
namespace fs = std::filesystem;

using Edits = std::vector<std::pair<std::string, std::string>>;

/// examples/<folder> copied into `dir`, with each text of `edits` in `design` replaced (each must
/// occur exactly once, so that an example's edit cannot silently stop applying).
void copy_example(const std::string& folder, const fs::path& dir, const std::string& design, const Edits& edits)
{
  fs::copy(fs::path(FIBERMOLD_SOURCE_DIR) / "examples" / folder, dir, fs::copy_options::recursive);
  std::string text = test::read_text(dir / design);
  for (const auto& [from, to] : edits) {
    const auto at = text.find(from);
    ASSERT_NE(at, std::string::npos) << design << ": no \"" << from << "\"";
    ASSERT_EQ(text.find(from, at + 1), std::string::npos) << design << ": \"" << from << "\" twice";
    text.replace(at, from.size(), to);
  }
  test::write_text(dir / design, text);
}

nlohmann::json read_json(const fs::path& file) { return nlohmann::json::parse(test::read_text(file)); }

/// README.txt's casting sheet read back against the files it is made from: each muscle cut to its
/// length inside the body (its spline in collide/fibers.json, 4,000 chords, each counted when its
/// midpoint is inside the body's mesh) within 1 mm; each shot's silicone the manifest's volume and
/// mass; each target's pressure per fiber collide's; the silicone's handling.
void expect_casting_sheet(const fs::path& build)
{
  const std::string sheet =
      std::regex_replace(test::read_text(build / "export" / "README.txt"), std::regex("\\s+"), " "); // unwrapped
  const TetMesh body = load_tet_mesh(build / "mesh" / "body.tetmesh");
  const SurfaceDistance skin(body.nodes, body.boundary_faces);
  const auto fibers = read_json(build / "collide" / "fibers.json");
  for (const auto& f : fibers["fibers"]) {
    const std::string name = f["name"];
    std::vector<Eigen::Vector3d> points, tangents;
    for (std::size_t i = 0; i < f["points_mm"].size(); ++i) {
      points.emplace_back(Eigen::Vector3d(f["points_mm"][i][0], f["points_mm"][i][1], f["points_mm"][i][2]) * 1e-3);
      tangents.emplace_back(Eigen::Vector3d(f["tangents_mm"][i][0], f["tangents_mm"][i][1], f["tangents_mm"][i][2]) *
                            1e-3);
    }
    const HermiteSpline spline(points, tangents);
    double inside = 0;
    for (int i = 0; i < 4000; ++i) {
      const Eigen::Vector3d a = spline.position(spline.spans() * i / 4000.0),
                            b = spline.position(spline.spans() * (i + 1) / 4000.0);
      if (skin.closest(0.5 * (a + b)).inside) inside += (b - a).norm() / 1e-3;
    }
    std::smatch cut;
    ASSERT_TRUE(std::regex_search(sheet, cut, std::regex(" " + name + R"(: ([0-9.]+) mm\. Fit the supply tube)")))
        << name << ": " << sheet;
    std::printf("%s: %s is cut to %s mm; inside the body it runs %.2f mm\n", build.parent_path().filename().c_str(),
                name.c_str(), cut[1].str().c_str(), inside);
    EXPECT_NEAR(std::stod(cut[1]), inside, 1.0) << name;
    for (const auto& [target, kPa] : f["pressure_kPa"].items())
      EXPECT_THAT(sheet, HasSubstr(fmt::format("{} {:.0f} kPa", name, kPa.get<double>()))) << target;
  }
  const auto manifest = read_json(build / "export" / "manifest.json");
  for (const auto& [shot, info] : manifest["shots"].items())
    EXPECT_THAT(sheet,
                HasSubstr(fmt::format("Inject about {:.1f} mL ({:.1f} g)", info["silicone_volume_mL"].get<double>(),
                                      info["silicone_mass_g"].get<double>())))
        << shot;
  for (const char* handling :
       {"Silicone: Smooth-On", "mixed 1A : 1B by weight; pot life", "demold after", "mold release"})
    EXPECT_THAT(sheet, HasSubstr(handling));
  // Each figure to measure comes with the command that predicts the cast robot again, on a line of its
  // own, naming one of the targets and this build folder.
  const std::string raw = test::read_text(build / "export" / "README.txt");
  const std::regex command(R"(\n      fibermold simulate (\S+) --as-built --target (\S+) --build-dir (\S+)\n)");
  std::size_t commands = 0;
  for (auto it = std::sregex_iterator(raw.begin(), raw.end(), command); it != std::sregex_iterator(); ++it) {
    ++commands;
    EXPECT_TRUE(fibers["fibers"][0]["pressure_kPa"].contains((*it)[2].str())) << it->str();
    const fs::path dir = (*it)[3].str();
    if (dir.is_absolute()) {
      EXPECT_TRUE(fs::equivalent(dir, build)) << it->str();
    }
  }
  std::size_t measures = 0;
  for (std::size_t at = raw.find("  Measure "); at != std::string::npos; at = raw.find("  Measure ", at + 1))
    ++measures;
  EXPECT_EQ(commands, measures);
  EXPECT_GT(commands, 0u);
}

void expect_parts_pass(const fs::path& build)
{
  ASSERT_NO_FATAL_FAILURE(expect_casting_sheet(build));
  const auto manifest = read_json(build / "export" / "manifest.json");
  ASSERT_EQ(manifest["parts"].size(), 4u);
  for (const auto& part : manifest["parts"]) EXPECT_TRUE(part["checks_passed"].get<bool>()) << part["name"];
  test::expect_fills(manifest);
  // Every target's deformed body to print beside the cast robot: a valid solid of the body's volume
  // (the silicone is nearly incompressible: within 3 %).
  const double body = load_tet_mesh(build / "mesh" / "body.tetmesh").volume() / 1e-6;
  const auto collide = read_json(build / "collide" / "report.json");
  EXPECT_EQ(manifest["deformed"].size(), collide["targets"].size());
  for (const auto& d : manifest["deformed"]) {
    std::printf("%s: %s %.2f mL (body %.2f mL), checks %s\n", build.parent_path().filename().c_str(),
                d["file"].get<std::string>().c_str(), d["volume_mL"].get<double>(), body,
                d["checks_passed"].get<bool>() ? "passed" : "FAILED");
    EXPECT_TRUE(fs::exists(build / "export" / d["file"].get<std::string>()));
    EXPECT_TRUE(d["checks_passed"].get<bool>()) << d["file"] << " " << d.value("problems", nlohmann::json()).dump();
    EXPECT_NEAR(d["volume_mL"].get<double>(), body, 0.03 * body) << d["file"];
  }
}

/// examples/<folder> with `edits` made to `design`, made to the end by `fibermold make` in `dir`:
/// every mold part passes its checks; `report` is optimize's report.json.
void make_example(const std::string& folder, const fs::path& dir, const Edits& edits, nlohmann::json& report)
{
  ASSERT_NO_FATAL_FAILURE(copy_example(folder, dir, "design.toml", edits));
  const auto r = test::run_fibermold("make design.toml --build-dir build", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ASSERT_NO_FATAL_FAILURE(expect_parts_pass(dir / "build"));
  report = read_json(dir / "build" / "optimize" / "report.json");
}

TEST(Demonstrators, CantileverMlsAgreesWithFemP2AtTheTip)
{
  // The field-wide comparison is tests/sim/cantilever_test.cpp; here the example as a user runs it.
  test::TempDir dir;
  ASSERT_NO_FATAL_FAILURE(
      copy_example("cantilever", dir.path(), "design.toml", {{"edge_length = 4.0", "edge_length = 6.0"}}));
  ASSERT_NO_FATAL_FAILURE(
      copy_example("cantilever", dir / "p2", "fem-p2.toml", {{"edge_length = 4.0", "edge_length = 6.0"}}));
  const auto largest = [](const std::string& out) {
    const auto at = out.find("max displacement ");
    return at == std::string::npos ? -1.0 : std::stod(out.substr(at + 17));
  };
  const auto mls = test::run_fibermold("simulate design.toml --build-dir build", dir.path());
  ASSERT_EQ(mls.exit_code, 0) << mls.err;
  const auto fem = test::run_fibermold("simulate fem-p2.toml --build-dir build", dir / "p2");
  ASSERT_EQ(fem.exit_code, 0) << fem.err;
  std::printf("cantilever tip: MLS-linear %.2f mm, fem-p2 %.2f mm\n", largest(mls.out + mls.err),
              largest(fem.out + fem.err));
  EXPECT_GT(largest(fem.out + fem.err), 40.0); // a large, non-linear sag
  EXPECT_NEAR(largest(mls.out + mls.err), largest(fem.out + fem.err), 0.04 * largest(fem.out + fem.err));
}

TEST(Demonstrators, RecoveryFindsTheSShapedMuscleAgainAndMakesMolds)
{
  // Paper, section VIII-B: the S-shaped muscle's deformation recovered to RMSE 0.10 mm and max
  // 0.20 mm on the centreline, from a start that bends the bar visibly differently.
  test::TempDir dir;
  nlohmann::json report;
  ASSERT_NO_FATAL_FAILURE(make_example(
      "recovery", dir.path(),
      {{"edge_length = 5.0", "edge_length = 8.0"}, {"max_iterations = 400", "max_iterations = 150"}}, report));
  const auto t = report["targets"]["s-bend"];
  std::printf("recovery: centreline RMSE %.3f → %.4f mm, max %.3f → %.4f mm (paper 0.10, 0.20)\n",
              t["start"]["rmse_mm"].get<double>(), t["rmse_mm"].get<double>(), t["start"]["max_error_mm"].get<double>(),
              t["max_error_mm"].get<double>());
  EXPECT_GT(t["start"]["rmse_mm"].get<double>(), 5.0);
  EXPECT_LT(t["rmse_mm"].get<double>(), 1.5 * 0.10);
  EXPECT_LT(t["max_error_mm"].get<double>(), 1.5 * 0.20);
}

TEST(Demonstrators, TwistingBarTwistsItsFreeEndAndMakesMolds)
{
  // Paper, section VIII-C: errors over the whole surface RMSE 1.9 mm, max 4.8 mm. The example runs
  // as a user runs it (its mesh is the paper's size), only the molds' voxels are coarser.
  test::TempDir dir;
  nlohmann::json report;
  ASSERT_NO_FATAL_FAILURE(make_example("twisting-bar", dir.path(), {{"voxel = 0.2 ", "voxel = 0.3 "}}, report));
  const auto t = report["targets"]["twist"];
  std::printf("twisting bar: surface RMSE %.2f → %.2f mm, max %.2f → %.2f mm (paper 1.9, 4.8)\n",
              t["start"]["surface_rmse_mm"].get<double>(), t["surface_rmse_mm"].get<double>(),
              t["start"]["surface_max_error_mm"].get<double>(), t["surface_max_error_mm"].get<double>());
  EXPECT_GT(t["start"]["surface_rmse_mm"].get<double>(), 5.0);
  EXPECT_LT(t["surface_rmse_mm"].get<double>(), 1.9);
  EXPECT_LT(t["surface_max_error_mm"].get<double>(), 4.8);
  // The muscle stays on: without the route-only start BFGS turned it down to 0 kPa (docs/optimize.md).
  EXPECT_GT(t["pressure_kPa"]["m1"].get<double>(), 20.0);
  // Its log follows the optimization with the time left (to the iteration limit).
  EXPECT_THAT(test::read_text(dir / "build" / "logs" / "optimize.log"),
              ::testing::ContainsRegex("progress [0-9]+ % \\(~[0-9]+ (s|min [0-9]+ s|min) left\\): iteration"));
}

TEST(Demonstrators, TwistingBarOptimizesAlikeUnderOtherBlasKernels)
{
  // OpenBLAS picks its kernels for the CPU (or takes OPENBLAS_CORETYPE), and each rounds dgemm and
  // dpotrf its own way, so the optimizer's path parts from another machine's within its first
  // iterations (docs/optimize.md, "The same design on other machines"). Run to a stopping rule the
  // example must end alike under Haswell's kernels (AVX2), Sandybridge's (AVX) and, where the CPU
  // has AVX-512, SkylakeX's (what OpenBLAS picks itself on the AMD EPYC this was measured on).
  // Measured (session 38; OpenBLAS 0.3.21, 44 s for the three on 2 cores): Haswell converged at
  // 406 iterations, f 0.6418, tracking RMSE 0.819 mm; Sandybridge 345, 0.6368, 0.806 mm; SkylakeX
  // 372, 0.6226, 0.821 mm. Before Levenberg-Marquardt forgot a secant term that claimed
  // convergence B alone did not (levenberg_marquardt.cpp), SkylakeX's run crawled on it to the
  // limit of 1000 at f 0.940. Session 49 (the bend barrier smooth where two bends swap, Sloan's
  // ordering; 30 s): 286, 304 and 306 iterations, f 0.5698 and RMSE 0.745 mm under all three. Under
  // Sloan's rounding with the barrier's sample at the tightest bend alone, Haswell's run stalled
  // at 471 on that sample's kink.
  const std::vector<std::string> kernels = test::blas_kernels();
  if (kernels.empty()) GTEST_SKIP() << "OpenBLAS takes no two kernels here (no AVX2, or it ignores OPENBLAS_CORETYPE)";
  std::vector<double> objectives, errors;
  for (const std::string& kernel : kernels) {
    test::TempDir dir;
    ASSERT_NO_FATAL_FAILURE(copy_example("twisting-bar", dir.path(), "design.toml", {}));
    const auto r = test::run_fibermold("make design.toml optimize --build-dir build", dir.path(),
                                       "env OPENBLAS_CORETYPE=" + kernel);
    ASSERT_EQ(r.exit_code, 0) << kernel << ": " << r.err;
    const auto report = read_json(dir / "build" / "optimize" / "report.json");
    objectives.push_back(report["objective"].get<double>());
    errors.push_back(report["targets"]["twist"]["rmse_mm"].get<double>());
    std::printf("twisting bar, kernel %s: %s after %d iterations, f %.4f, tracking RMSE %.3f mm\n", kernel.c_str(),
                report["termination"].get<std::string>().c_str(), report["iterations"].get<int>(), objectives.back(),
                errors.back());
    EXPECT_EQ(report["termination"].get<std::string>(), "converged") << kernel;
    EXPECT_LT(objectives.back(), 0.66) << kernel;
  }
  const auto [f_low, f_high] = std::minmax_element(objectives.begin(), objectives.end());
  const auto [e_low, e_high] = std::minmax_element(errors.begin(), errors.end());
  EXPECT_LT(*f_high / *f_low, 1.05);
  EXPECT_LT(*e_high / *e_low, 1.03);
}

TEST(Demonstrators, ContinuumRobotBendsInSpaceMakesMoldsAndRerunsOnlyMoldsAfterAMoldEdit)
{
  // Paper, section VIII-D: errors on the tracking curve RMSE 1.7 mm, max 3.2 mm (on its own target;
  // ours is made by make_robot.py). The full example reaches 0.59 and 1.23 mm in 183 iterations;
  // this coarse one 1.62 and 2.66 mm after its 100.
  test::TempDir dir;
  const Edits coarse{{"edge_length = 8.0", "edge_length = 10.0"},
                     {"max_iterations = 200", "max_iterations = 100"},
                     {"voxel = 0.25", "voxel = 0.3"}};
  nlohmann::json report;
  ASSERT_NO_FATAL_FAILURE(make_example("continuum-robot", dir.path(), coarse, report));
  const auto t = report["targets"]["spatial-bend"];
  std::printf("continuum robot: tracking RMSE %.2f → %.2f mm, max %.2f → %.2f mm (paper 1.7, 3.2)\n",
              t["start"]["rmse_mm"].get<double>(), t["rmse_mm"].get<double>(), t["start"]["max_error_mm"].get<double>(),
              t["max_error_mm"].get<double>());
  EXPECT_GT(t["start"]["rmse_mm"].get<double>(), 80.0); // the target moves the tip 221 mm
  EXPECT_LT(t["rmse_mm"].get<double>(), 1.5 * 1.7);
  EXPECT_LT(t["max_error_mm"].get<double>(), 1.5 * 3.2);

  Edits thicker = coarse;
  thicker.emplace_back("wall = 4.0", "wall = 5.0");
  ASSERT_NO_FATAL_FAILURE(copy_example("continuum-robot", dir / "edit", "design.toml", thicker));
  fs::copy_file(dir / "edit" / "design.toml", dir / "design.toml", fs::copy_options::overwrite_existing);
  const auto again = test::run_fibermold("make design.toml --build-dir build", dir.path());
  ASSERT_EQ(again.exit_code, 0) << again.err;
  const std::string log = again.out + again.err;
  EXPECT_THAT(log, HasSubstr("molds: running ([mold].wall changed"));
  EXPECT_THAT(log, HasSubstr("export: running"));
  EXPECT_THAT(log, HasSubstr("2 stage(s) ran, 4 fresh"));
  EXPECT_THAT(log, ::testing::Not(HasSubstr("optimize: running")));
  expect_parts_pass(dir / "build");
}

TEST(Demonstrators, TentacleErrorsWithinThePapersTipOnlyMatchesLessOfTheBodyAndFullLengthMakesMolds)
{
  // Paper, Fig. 13, errors over the whole surface: full length RMSE 20.3 mm, max 29.5; tip only
  // 24.0, 39.6. Full length as the example is, to printable molds; tip only with 30 iterations, up
  // to collide. The molds are those of the example's route: other routes (30 iterations; or a
  // 12 mm mesh, as until session 21) trap 1.5 mm³ of air in shot 2 near (108, 9, 3.6) mm with four
  // vents placed, or, with "auto" parting, leave the 6 mm tip a mold wall of 0.01–0.32 mm.
  test::TempDir dir;
  const Edits coarse{{"max_iterations = 300", "max_iterations = 30"}};
  ASSERT_NO_FATAL_FAILURE(copy_example("tentacle", dir.path(), "full.toml", {}));
  ASSERT_NO_FATAL_FAILURE(copy_example("tentacle", dir / "tip", "tip.toml", coarse));
  std::map<std::string, nlohmann::json> result;
  for (const auto& [condition, cwd] : {std::pair{"full", dir.path()}, std::pair{"tip", dir / "tip"}}) {
    const bool molds = condition == std::string("full");
    const auto r = test::run_fibermold(
        std::string("make ") + condition + ".toml" + (molds ? "" : " collide") + " --build-dir build", cwd);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    if (molds) expect_parts_pass(cwd / "build");
    result[condition] = read_json(cwd / "build" / "optimize" / "report.json")["targets"]["curl"];
    std::printf("tentacle %s: surface RMSE %.2f mm, max %.2f mm; tracking RMSE %.2f mm\n", condition,
                result[condition]["surface_rmse_mm"].get<double>(),
                result[condition]["surface_max_error_mm"].get<double>(), result[condition]["rmse_mm"].get<double>());
  }
  EXPECT_LT(result["full"]["surface_rmse_mm"].get<double>(), 1.5 * 20.3);
  EXPECT_LT(result["full"]["surface_max_error_mm"].get<double>(), 1.5 * 29.5);
  EXPECT_LT(result["tip"]["surface_rmse_mm"].get<double>(), 1.5 * 24.0);
  EXPECT_LT(result["tip"]["surface_max_error_mm"].get<double>(), 1.5 * 39.6);
  // As in the paper: matching the tip only leaves the rest of the body further off.
  EXPECT_GT(result["tip"]["surface_rmse_mm"].get<double>(), result["full"]["surface_rmse_mm"].get<double>());
}

TEST(Demonstrators, WalkingRobotMusclesAreOptimizedMovedApartAndMolded)
{
  // Paper, section VIII-F: no errors given. Both poses are optimized together with the muscles
  // moved apart at the start (twist-a starts touching the spine) and kept apart by the clearance
  // barrier, so collide finds every clearance held and changes nothing, and both shots of molds
  // pass their checks.
  test::TempDir dir;
  nlohmann::json report;
  // The example's own mesh and iterations (its limit of 100 since session 44): cut to 30
  // iterations on a 6 mm mesh, as this test once was, the twist ended at 0.55 mm under Haswell's
  // kernels and at 0.99 and 1.42 mm under Sandybridge's and SkylakeX's, far from done.
  ASSERT_NO_FATAL_FAILURE(make_example("walking-robot", dir.path(), {{"voxel = 0.2 ", "voxel = 0.3 "}}, report));
  const auto optimized = report["targets"];
  const auto collide = read_json(dir / "build" / "collide" / "report.json");
  for (const char* target : {"bend", "twist"}) {
    const auto& t = optimized[target];
    const auto& c = collide["targets"][target];
    std::printf("walking robot %s: tracking RMSE %.2f → %.2f mm optimized, %.2f mm after collide\n", target,
                t["start"]["rmse_mm"].get<double>(), c["before"]["rmse_mm"].get<double>(),
                c["after"]["rmse_mm"].get<double>());
    // Measured (session 38): bend 0.59 and twist 0.46 mm under Haswell's kernels, 0.58 and 0.46 mm
    // under Sandybridge's, 0.60 and 0.48 mm under SkylakeX's (docs/optimize.md, "The walking
    // robot's twist"); session 43, with the exit ramp measured on the route as it is: 0.63 and
    // 0.51 mm under Haswell's.
    EXPECT_EQ(c["after"]["rmse_mm"].get<double>(), c["before"]["rmse_mm"].get<double>()) << target;
  }
  EXPECT_LT(collide["targets"]["bend"]["before"]["rmse_mm"].get<double>(),
            optimized["bend"]["start"]["rmse_mm"].get<double>() * 0.6);
  // The robot twists (issue #38): after collide, at most half the error of the robot at rest, whose
  // front tracking curve (12 samples across y = -8..8 mm at x = 40 mm) twist.obj turns by 15° × 40/42
  // about the x axis: 1.25 mm RMS. The chord of its end samples is checked against the targets
  // stage's own reading of twist.obj (its poses: 1.99 mm). The five-muscle layout's spine is what
  // makes it (with the twist pair and one bend muscle alone it stayed at 1.17 mm).
  const double angle = 15.0 * 40 / 42 * M_PI / 180;
  const auto chord = [&](double y) { return 2 * std::abs(y) * std::sin(angle / 2); };
  const auto targets = read_json(dir / "build" / "targets" / "report.json");
  ASSERT_EQ(targets["twist"]["poses"].size(), 2u); // the curve's first and last points
  for (const auto& pose : targets["twist"]["poses"]) {
    const auto& at = pose["rest_mm"];
    const Eigen::Vector3d moved(pose["translation_mm"][0].get<double>(), pose["translation_mm"][1].get<double>(),
                                pose["translation_mm"][2].get<double>());
    EXPECT_NEAR(moved.norm(), chord(at[1].get<double>()), 0.01 * chord(8.0)) << pose["place"];
  }
  double unactuated = 0;
  for (int k = 0; k < 12; ++k) unactuated += std::pow(chord(-8 + 16.0 * k / 11), 2);
  unactuated = std::sqrt(unactuated / 12);
  EXPECT_LE(collide["targets"]["twist"]["after"]["rmse_mm"].get<double>(), 0.5 * unactuated);
  // Both twist muscles end pressurized for the twist (the right-handed pair of sessions 15-22 ended
  // switched off, at 0-2.6 kPa, and the twist at the unactuated error): twist-a at 174-179 kPa and
  // twist-b, the helix over the axis, weak at 23-31 kPa under the kernels above (docs/optimize.md).
  std::printf("walking robot twist: twist-a %.1f kPa, twist-b %.1f kPa\n",
              optimized["twist"]["pressure_kPa"]["twist-a"].get<double>(),
              optimized["twist"]["pressure_kPa"]["twist-b"].get<double>());
  for (const char* muscle : {"twist-a", "twist-b"})
    EXPECT_GT(optimized["twist"]["pressure_kPa"][muscle].get<double>(), 0.04 * 425) << muscle;
  EXPECT_LE(report["objective"].get<double>(), report["first_guess"]["objective"].get<double>());
  EXPECT_TRUE(report["fibers_kept_apart"].get<bool>());
  EXPECT_FALSE(collide["changed"].get<bool>());
  EXPECT_GE(collide["smallest_clearance_mm"]["before"].get<double>(), 1.0 - 1e-3);
}

TEST(Demonstrators, NotchedFingerCurlsTowardItsPoseAndSaysHowMuchAndMakesMolds)
{
  // A body a user would bring, with a pose target: the tip turned 60° about z. The targets stage
  // reaches the pose; the optimized muscle curls the finger part of the way, and optimize's report
  // and report.html say how far.
  test::TempDir dir;
  nlohmann::json report;
  ASSERT_NO_FATAL_FAILURE(make_example("notched-finger", dir.path(),
                                       {{"edge_length = 4.0", "edge_length = 6.0"},
                                        {"max_iterations = 200", "max_iterations = 40"},
                                        {"voxel = 0.25", "voxel = 0.4"}},
                                       report));
  const auto targets = read_json(dir / "build" / "targets" / "report.json")["curl"]["poses"][0];
  EXPECT_NEAR(targets["rotation_about_asked_axis_deg"].get<double>(), 60, 1.0);
  const auto& pose = report["targets"]["curl"]["poses"][0];
  const double reached = pose["rotation_about_asked_axis_deg"].get<double>();
  std::printf(
      "notched finger: the pose target turns the tip %.2f°; the optimized muscle %.2f° of 60° (%.0f %%) at %.0f kPa\n",
      targets["rotation_about_asked_axis_deg"].get<double>(), reached, pose["rotation_reached_percent"].get<double>(),
      report["targets"]["curl"]["pressure_kPa"]["flexor"].get<double>());
  EXPECT_GT(reached, 50); // measured 56.9° after 40 iterations on 6 mm edges (docs/targets.md)
  EXPECT_LT(reached, 62);
  const std::string html = test::read_text(dir / "build" / "export" / "report.html");
  EXPECT_THAT(html, HasSubstr("turn reached"));
  EXPECT_THAT(html, HasSubstr(fmt::format("{:.1f}° of 60.0° (pose[1])", reached)));
}

} // namespace
} // namespace fibermold
