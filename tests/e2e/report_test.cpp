// The report users open first (export/report.html) for a design with a target: the body deformed
// under the final routing beside the molds, each target's error before and after collide as collide
// measured it, what collide changed, and the optimizer's history as a plot; it draws in headless
// Chromium without a script error.
#include <algorithm>
#include <cstring>
#include <regex>
#include <sstream>

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "mesh/surface_import.hpp"
#include "mesh/surface_mesh.hpp"
#include "mesh/tet_mesh.hpp"
#include "sim/hermite_spline.hpp"
#include "test_support.hpp"

namespace fibermold {
namespace {

using ::testing::HasSubstr;
namespace fs = std::filesystem;

// A tracking curve of three points: the report draws it along its spline.
const std::string kDesign =
    std::string(test::kBarDesign) + test::kBarMuscle +
    "[[tracking_curve]]\nname = \"centre\"\npoints = [[0, 0, 0], [30, 0, 1], [60, 0, 0]]\nsamples = 20\n" +
    test::kBarTarget + "[optimize]\nmax_iterations = 3\n[mold]\nvoxel = 0.4\n";

TEST(ReportE2E, ShowsTheDeformedBodyTheErrorsAndTheOptimizationHistory)
{
  test::TempDir dir;
  test::write_bar(dir.path());
  test::write_text(dir / "design.toml", kDesign);
  const auto r = test::run_fibermold("make design.toml --build-dir build", dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const fs::path build = dir / "build";
  const std::string html = test::read_text(build / "export" / "report.html");

  // The errors are collide's, to the micrometre.
  const auto collide = nlohmann::json::parse(test::read_text(build / "collide" / "report.json"));
  const auto& s = collide["targets"]["s"];
  const std::string row = fmt::format("<tr><td>s</td><td>{:.3f}</td><td>{:.3f}</td>",
                                      s["before"]["rmse_mm"].get<double>(), s["after"]["rmse_mm"].get<double>());
  EXPECT_THAT(html, HasSubstr("Targets: error over the tracking curves and the surface (mm)"));
  EXPECT_THAT(html, HasSubstr(row));
  EXPECT_THAT(html, HasSubstr("none: every fiber was clear"));
  // Which hole is which: each shot's sprue and vents drawn and named in the 3D view's legend.
  const auto molds = nlohmann::json::parse(test::read_text(build / "molds" / "report.json"));
  for (const char* shot : {"shot1", "shot2"}) {
    const auto& fill = molds["shots"][shot]["fill"];
    ASSERT_EQ(fill["sprues"].size(), 1u) << shot;
    EXPECT_THAT(html,
                HasSubstr(fmt::format("\"{} sprue, from {}\"", shot, fill["sprues"][0]["from"].get<std::string>())));
    for (std::size_t k = 1; k <= fill["vents"].size(); ++k)
      EXPECT_THAT(html, HasSubstr(fmt::format("\"{} vent {}\"", shot, k)));
    EXPECT_THAT(html, ::testing::Not(HasSubstr(fmt::format("\"{} vent {}\"", shot, fill["vents"].size() + 1))));
  }
  EXPECT_EQ(molds["shots"]["shot1"]["fill"]["sprues"][0]["from"], "below");
  EXPECT_EQ(molds["shots"]["shot2"]["fill"]["sprues"][0]["from"], "above");
  // Each fiber's smallest bend radius as collide left it, against the muscle's limit.
  const double limit = collide["min_bend_radius_mm"].get<double>();
  EXPECT_GT(limit, 0);
  EXPECT_THAT(
      html, HasSubstr(fmt::format("Bend radius: each fiber's smallest, as built (the muscle takes {:.3f} mm)", limit)));
  const auto& bend = collide["bends"]["m1"];
  if (bend.contains("min_bend_radius_mm")) {
    EXPECT_GE(bend["min_bend_radius_mm"].get<double>(), limit);
    EXPECT_THAT(html,
                HasSubstr(fmt::format("<tr><td>m1</td><td>{:.3f}</td>", bend["min_bend_radius_mm"].get<double>())));
  } else {
    EXPECT_EQ(bend["straight"], true);
    EXPECT_THAT(html, HasSubstr("<tr><td>m1</td><td>straight</td>"));
  }
  // The casting guide says it too, where the muscles are laid into their grooves.
  const std::string guide = test::read_text(build / "export" / "README.txt");
  std::istringstream readme(guide); // a plain-text file read in any editor: no line over 100 characters
  for (std::string line; std::getline(readme, line);)
    EXPECT_LE(std::count_if(line.begin(), line.end(), [](char c) { return (c & 0xC0) != 0x80; }), 100) << line;
  EXPECT_THAT(guide, HasSubstr(fmt::format("The muscles take bends no tighter than {:.1f} mm in radius", limit)));
  EXPECT_THAT(guide,
              HasSubstr(bend.contains("min_bend_radius_mm")
                            ? fmt::format("  m1: {:.1f} mm, {:.1f} mm along it",
                                          bend["min_bend_radius_mm"].get<double>(), bend["along_mm"].get<double>())
                            : std::string("  m1: straight")));

  // The optimization: start, first guess and end errors (RMSE and the turn's, the tracking curve
  // tracking orientation), how much was reached, the pressure; its warnings (3 iterations: stopped
  // at the limit) as the banner.
  const auto optimize = nlohmann::json::parse(test::read_text(build / "optimize" / "report.json"));
  const auto& o = optimize["targets"]["s"];
  const auto& guess = optimize["first_guess"]["targets"]["s"];
  EXPECT_THAT(html, HasSubstr("Optimization: iteration limit after 3 iterations"));
  EXPECT_THAT(html, HasSubstr(fmt::format(
                        "<tr><td>s</td><td>{:.3f}</td><td>{:.3f}</td><td>{:.3f}</td><td>{:.1f}</td>"
                        "<td>{:.1f}</td><td>{:.1f}</td><td>{:.0f} %</td><td>{:.0f} %</td><td>{:.1f}</td></tr>",
                        o["start"]["rmse_mm"].get<double>(), guess["rmse_mm"].get<double>(), o["rmse_mm"].get<double>(),
                        o["start"]["orientation_rms_deg"].get<double>(), guess["orientation_rms_deg"].get<double>(),
                        o["orientation_rms_deg"].get<double>(), o["reached_percent"].get<double>(),
                        100 * (1 - o["rmse_mm"].get<double>() / guess["rmse_mm"].get<double>()),
                        o["pressure_kPa"]["m1"].get<double>())));
  // The turn's error is the angle between the turns reached and asked: under the largest turn anywhere.
  EXPECT_GT(o["orientation_rms_deg"].get<double>(), 0);
  EXPECT_LE(o["orientation_rms_deg"].get<double>(), o["orientation_max_deg"].get<double>());
  EXPECT_THAT(html, HasSubstr("<div id=\"warnings\"><strong>Warnings</strong>"));
  EXPECT_THAT(html,
              HasSubstr("<li>the optimizer stopped before converging (iteration limit: 3 iterations, the limit)"));
  // README.txt says so too, before how to check the cast robot against the simulation.
  const std::size_t warned = guide.find("\nThe optimization warned (report.html gives its figures)"),
                    stopped = guide.find("\n  - the optimizer stopped before converging (iteration limit: 3 "),
                    checking = guide.find("\nChecking the cast robot against the simulation\n");
  ASSERT_NE(warned, std::string::npos);
  EXPECT_GT(stopped, warned);
  EXPECT_GT(checking, stopped);
  EXPECT_NE(checking, std::string::npos);

  // One plot point per optimizer iteration, for both series.
  const std::string history = test::read_text(build / "optimize" / "history.csv");
  const long iterations = std::count(history.begin(), history.end(), '\n') - 1;
  ASSERT_GT(iterations, 0);
  const std::regex polyline("<polyline [^>]*points=\"([^\"]*)\"");
  int series = 0;
  for (auto it = std::sregex_iterator(html.begin(), html.end(), polyline); it != std::sregex_iterator();
       ++it, ++series) {
    const std::string points = (*it)[1];
    EXPECT_EQ(std::count(points.begin(), points.end(), ','), iterations) << "series " << series;
  }
  EXPECT_EQ(series, 2);

  // The deformed body is the target's equilibrium, not the body at rest: the free end moved.
  const TetMesh rest = load_tet_mesh(build / "mesh" / "body.tetmesh");
  const auto deformed = nlohmann::json::parse(test::read_text(build / "collide" / "deformed-s.json"));
  ASSERT_EQ(deformed["nodes_mm"].size(), static_cast<std::size_t>(rest.nodes.rows()));
  double moved = 0;
  for (Eigen::Index i = 0; i < rest.nodes.rows(); ++i)
    for (int k = 0; k < 3; ++k)
      moved = std::max(
          moved, std::abs(deformed["nodes_mm"][static_cast<std::size_t>(i)][static_cast<std::size_t>(k)].get<double>() -
                          rest.nodes(i, k) / 1e-3));
  std::printf("report: the deformed body's nodes moved up to %.2f mm\n", moved);
  EXPECT_GT(moved, 1.0);

  // deformed-s.stl: that deformed skin to print and hold against the cast robot, in the body's
  // frame (float32 mm), closed; the manifest lists it and README.txt says what to compare.
  const SurfaceMesh overlay = import_surface(build / "export" / "deformed-s.stl", 1e-3);
  EXPECT_EQ(overlay.num_faces(), rest.boundary_faces.rows());
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e9), hi = -lo;
  for (Eigen::Index f = 0; f < rest.boundary_faces.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      for (int c = 0; c < 3; ++c) {
        const double v = deformed["nodes_mm"][static_cast<std::size_t>(rest.boundary_faces(f, k))][c].get<double>();
        lo(c) = std::min(lo(c), v), hi(c) = std::max(hi(c), v);
      }
  EXPECT_LT((overlay.vertices.colwise().minCoeff().transpose() / 1e-3 - lo).norm(), 1e-3);
  EXPECT_LT((overlay.vertices.colwise().maxCoeff().transpose() / 1e-3 - hi).norm(), 1e-3);
  // Nearly incompressible silicone: the bent bar holds the rest volume within 2 %.
  EXPECT_NEAR(signed_volume(overlay), rest.volume(), 0.02 * rest.volume());
  const auto manifest = nlohmann::json::parse(test::read_text(build / "export" / "manifest.json"));
  ASSERT_EQ(manifest["deformed"].size(), 1u);
  EXPECT_EQ(manifest["deformed"][0]["file"], "deformed-s.stl");
  EXPECT_TRUE(manifest["deformed"][0]["checks_passed"].get<bool>());
  const auto fibers = nlohmann::json::parse(test::read_text(build / "collide" / "fibers.json"));
  EXPECT_THAT(guide, HasSubstr(fmt::format("Target \"s\": drive the muscles at m1 {:.0f} kPa gauge (at most 425 kPa",
                                           fibers["fibers"][0]["pressure_kPa"]["s"].get<double>())));
  // The casting sheet cuts the muscle to its length inside the bar [0, 60] × [−8, 8]² mm, measured
  // here on the spline itself: 20,000 chords, each counted when its midpoint is inside.
  const auto& f = fibers["fibers"][0];
  std::vector<Eigen::Vector3d> points, tangents;
  for (std::size_t i = 0; i < f["points_mm"].size(); ++i) {
    points.emplace_back(f["points_mm"][i][0], f["points_mm"][i][1], f["points_mm"][i][2]);
    tangents.emplace_back(f["tangents_mm"][i][0], f["tangents_mm"][i][1], f["tangents_mm"][i][2]);
  }
  const HermiteSpline spline(points, tangents);
  double inside = 0;
  for (int i = 0; i < 20000; ++i) {
    const Eigen::Vector3d a = spline.position(spline.spans() * i / 20000.0),
                          b = spline.position(spline.spans() * (i + 1) / 20000.0), m = 0.5 * (a + b);
    if (m.x() > 0 && m.x() < 60 && std::abs(m.y()) < 8 && std::abs(m.z()) < 8) inside += (b - a).norm();
  }
  std::smatch cut;
  ASSERT_TRUE(std::regex_search(guide, cut, std::regex(R"(\n  m1: ([0-9.]+) mm\. Fit the supply tube)"))) << guide;
  std::printf("report: m1 is cut to %s mm; inside the bar it runs %.2f mm\n", cut[1].str().c_str(), inside);
  EXPECT_NEAR(std::stod(cut[1]), inside, 1.0);

  bool compared = false;
  for (const auto& pose : s["poses"])
    if (pose["place"] == "centre, last point") {
      const auto& t = pose["translation_mm"];
      const double norm = std::hypot(t[0].get<double>(), t[1].get<double>(), t[2].get<double>());
      EXPECT_GT(norm, 1.0);
      // Named with where it is on the robot: the curve's last point, (60, 0, 0) mm.
      EXPECT_NEAR(pose["rest_mm"][0].get<double>(), 60, 1e-9);
      EXPECT_NEAR(std::hypot(pose["rest_mm"][1].get<double>(), pose["rest_mm"][2].get<double>()), 0, 1e-9);
      EXPECT_THAT(guide, HasSubstr(fmt::format("    centre, last point (at (60.0, 0.0, 0.0) mm at rest): moves {:.1f} "
                                               "mm ({:.1f}, {:.1f}, {:.1f})",
                                               norm, t[0].get<double>(), t[1].get<double>(), t[2].get<double>())));
      compared = true;
    }
  EXPECT_TRUE(compared) << "collide reports where the tracking curve's end went";
  // The one figure to measure, and how much it hinges on the least certain inputs (collide solves the
  // target again with the silicone and the pressure 10 % off): README.txt gives collide's figures.
  // How to mount it: as simulated, under the default gravity (0, 0, −9.81) m/s².
  EXPECT_THAT(std::regex_replace(guide, std::regex("\\s+"), " "),
              HasSubstr("Mount the robot as it was simulated: held at its fixed faces, with the design's direction "
                        "(0.00, 0.00, -1.00) pointing down ([material] gravity)."));
  const std::size_t measure_at = guide.find("\n  Measure ");
  ASSERT_NE(measure_at, std::string::npos) << guide;
  const std::size_t measure_end = guide.find("\n      fibermold simulate ", measure_at); // the command after it
  ASSERT_NE(measure_end, std::string::npos) << guide;
  const std::string unwrapped =
      std::regex_replace(guide.substr(measure_at + 3, measure_end - measure_at - 3), std::regex("\n  "), " ");
  std::smatch measure;
  ASSERT_TRUE(std::regex_search(
      unwrapped, measure,
      std::regex(R"(^Measure (.+?)'s (turn|move)[^:]*: ([0-9.]+)(°| mm) in the simulation\. To measure it, [^.]*\. )"
                 R"(Before you pressurize it \(every muscle at 0 kPa\), held as simulated, its weight alone )"
                 R"((?:turns|moves) it ([0-9.]+)(?:°| mm) in the simulation: compare that first\. )"
                 R"(With the least certain inputs 10 % off:)")))
      << unwrapped;
  bool measured = false;
  for (const auto& pose : s["poses"]) {
    if (pose["place"] != measure[1].str()) continue;
    measured = true;
    const auto& v = pose["sensitivity"][measure[2] == "turn" ? "rotation_deg" : "displacement_mm"];
    const auto& t = pose["translation_mm"];
    const double nominal = measure[2] == "turn"
                               ? pose["rotation_deg"].get<double>()
                               : std::hypot(t[0].get<double>(), t[1].get<double>(), t[2].get<double>());
    EXPECT_NEAR(std::stod(measure[3]), nominal, 0.05);
    // Its weight alone (the bar under gravity, the muscle at 0 kPa): part of the way, the same way.
    const double weight = pose["unpressurized"][measure[2] == "turn" ? "rotation_deg" : "displacement_mm"];
    EXPECT_NEAR(std::stod(measure[5]), weight, 0.05);
    EXPECT_GT(weight, 0.1 * nominal);
    EXPECT_LT(weight, nominal);
    const std::string unit = measure[4];
    EXPECT_THAT(unwrapped, HasSubstr(fmt::format("{:.1f}{} and {:.1f}{} with the silicone 10 % stiffer and",
                                                 v["stiffer"].get<double>(), unit, v["softer"].get<double>(), unit)));
    std::printf(
        "report: measure %s's %s: %.2f; silicone stiffer %.2f, softer %.2f; pressure -10 %% %.2f, +10 %% %.2f\n",
        measure[1].str().c_str(), measure[2].str().c_str(), nominal, v["stiffer"].get<double>(),
        v["softer"].get<double>(), v["less_pressure"].get<double>(), v["more_pressure"].get<double>());
    // A muscle that contracts with its pressure moves the bar further at more pressure; 10 % less or
    // more moves it by 2–20 %.
    EXPECT_LT(v["less_pressure"].get<double>(), 0.98 * nominal);
    EXPECT_GT(v["less_pressure"].get<double>(), 0.8 * nominal);
    EXPECT_GT(v["more_pressure"].get<double>(), 1.02 * nominal);
    EXPECT_LT(v["more_pressure"].get<double>(), 1.2 * nominal);
    // The silicone 10 % off changes it by less than 10 %, but changes it, the two ways apart.
    const double stiffer = v["stiffer"].get<double>() - nominal, softer = v["softer"].get<double>() - nominal;
    EXPECT_LT(std::abs(stiffer), 0.1 * nominal);
    EXPECT_LT(std::abs(softer), 0.1 * nominal);
    EXPECT_GT(std::min(std::abs(stiffer), std::abs(softer)), 1e-3 * nominal);
    EXPECT_LT(stiffer * softer, 0);
  }
  EXPECT_TRUE(measured) << measure[1] << " is none of collide's poses";
  if (std::system("command -v admesh >/dev/null 2>&1") == 0) {
    const auto a = test::admesh(build / "export" / "deformed-s.stl");
    EXPECT_EQ(a.at("Number of parts"), 1);
    EXPECT_EQ(a.at("Degenerate facets"), 0);
    EXPECT_EQ(a.at("Edges fixed"), 0);
    EXPECT_EQ(a.at("Facets removed"), 0);
    EXPECT_EQ(a.at("Backwards edges"), 0);
  }

  if (std::system("command -v chromium >/dev/null 2>&1") != 0)
    GTEST_SKIP() << "chromium is not installed (scripts/setup installs it)";
  // Shown: the groove body, shot 1's parts, the deformed body and the target beside it; on the
  // page, also shot 2's parts and the body at rest.
  const long body = load_tet_mesh(build / "mesh" / "body.tetmesh").boundary_faces.rows();
  const std::string groove = test::read_text(build / "molds" / "groove-body.stl");
  std::uint32_t groove_triangles = 0;
  std::memcpy(&groove_triangles, groove.data() + 80, sizeof groove_triangles);
  long shown = groove_triangles + 2 * body, all = shown + body;
  for (const auto& [name, part] : molds["parts"].items()) {
    all += part["triangles"].get<long>();
    if (part["shot"] == "shot1") shown += part["triangles"].get<long>();
  }
  const auto [code, dom] = test::open_in_browser(build / "export" / "report.html", dir / "report.png");
  ASSERT_EQ(code, 0) << dom;
  std::smatch status;
  ASSERT_TRUE(
      std::regex_search(dom, status, std::regex(R"(drawn (\d+) of (\d+) triangles, (\d+) of (\d+) pixels painted)")))
      << dom.substr(0, 2000);
  EXPECT_EQ(std::stol(status[1]), shown);
  EXPECT_EQ(std::stol(status[2]), all);
  EXPECT_THAT(dom, ::testing::Not(HasSubstr("Uncaught")));
  // A legend: every item of the 3D view has its colour beside its name, a square for a surface,
  // a dash for a line (the fiber m1 and the tracking curve among them).
  const std::regex swatch(R"re(<label><input type="checkbox"><span class="swatch (surface|line)" )re"
                          R"re(style="background: rgb\((\d+), (\d+), (\d+)\);"></span>([^<]+)</label>)re");
  int surfaces = 0, lines = 0;
  std::string names;
  for (auto it = std::sregex_iterator(dom.begin(), dom.end(), swatch); it != std::sregex_iterator(); ++it) {
    ((*it)[1] == "surface" ? surfaces : lines) += 1;
    names += (*it)[5].str() + "|";
  }
  std::printf("report legend: %d surfaces, %d lines: %s\n", surfaces, lines, names.c_str());
  EXPECT_EQ(surfaces,
            1 + static_cast<int>(molds["parts"].size()) + 3); // groove body, parts, deformed body, target, body at rest
  EXPECT_THAT(names, HasSubstr("target s (asked) |"));
  EXPECT_GE(lines, 2);
  EXPECT_THAT(names, HasSubstr("m1 |"));
  EXPECT_EQ(test::read_text(dir / "report.png").substr(1, 3), "PNG");
}

} // namespace
} // namespace fibermold
