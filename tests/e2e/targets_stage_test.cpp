// The targets stage as a user runs it: forces, fibers and surface targets on a small bar.
#include <cmath>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/array_file.hpp"
#include "export/stl_writer.hpp"
#include "mesh/mesh_quality.hpp"
#include "mesh/surface_import.hpp"
#include "mesh/tet_mesh.hpp"
#include "primitives.hpp"
#include "sim/mls_basis.hpp"
#include "test_support.hpp"

namespace fibermold {
namespace {

using ::testing::ContainsRegex;
using ::testing::HasSubstr;
namespace fs = std::filesystem;

const char* kDesign = R"([design]
name = "bar"
surface = "bar.stl"
[mesh]
edge_length = 6
[material]
gravity = [0, 0, 0]
[[fixed]]
box = { min = [-1, -9, -9], max = [0.5, 9, 9] }
[[fiber]]
name = "m1"
points = [[0, 0, 0], [30, 3, 0], [60, 0, 0]]
[mold]
wall = 4.0
)";

class TargetsE2E : public ::testing::Test {
protected:
  void SetUp() override { write_stl(dir_ / "bar.stl", bar_); }
  void design(const std::string& targets) { test::write_text(dir_ / "design.toml", std::string(kDesign) + targets); }
  test::CommandResult make() { return test::run_fibermold("make design.toml targets --build-dir build", dir_.path()); }
  nlohmann::json report() { return nlohmann::json::parse(test::read_text(dir_ / "build" / "targets" / "report.json")); }

  test::TempDir dir_;
  const SurfaceMesh bar_ = test::box({0, -0.008, -0.008}, {0.06, 0.008, 0.008}, Eigen::Vector3i(10, 3, 3));
};

TEST_F(TargetsE2E, ForcesAndFibersTargets)
{
  design(R"([[target]]
name = "droop"
kind = "forces"
load = [{ box = { min = [59, -9, -9], max = [61, 9, 9] }, force = [0, 0, -0.05] }]
[[target]]
name = "curl"
kind = "fibers"
fibers = [{ name = "m1", pressure = 300 }]
)");
  const auto r = make();
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto rep = report();
  EXPECT_EQ(rep["droop"]["kind"], "forces");
  EXPECT_GT(rep["droop"]["max_displacement_mm"].get<double>(), 1.0);
  EXPECT_GT(rep["curl"]["max_displacement_mm"].get<double>(), 0.5);
  const TetMesh mesh = load_tet_mesh(dir_ / "build" / "mesh" / "body.tetmesh");
  const Eigen::VectorXd x = load_array(dir_ / "build" / "targets" / "droop.positions", "positions");
  EXPECT_EQ(x.size(), 3 * mesh.nodes.rows());
  EXPECT_TRUE(fs::exists(dir_ / "build" / "targets" / "curl.vtu"));
}

TEST_F(TargetsE2E, SurfaceTargetIsFilledInAndFollowed)
{
  // The bar bent upward: z += 0.05 x² / 60 mm (3 mm at the free end).
  const auto bend = [](const Eigen::Vector3d& X) -> Eigen::Vector3d {
    return X + Eigen::Vector3d(0, 0, 0.05 * X.x() * X.x() / 0.06);
  };
  SurfaceMesh bent = bar_;
  for (Eigen::Index v = 0; v < bent.num_vertices(); ++v)
    bent.vertices.row(v) = bend(bar_.vertices.row(v).transpose()).transpose();
  write_stl(dir_ / "bent.stl", bent);
  design("[[target]]\nname = \"bend\"\nkind = \"surface\"\nsurface = \"bent.stl\"\n");
  const auto r = make();
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NEAR(report()["bend"]["max_displacement_mm"].get<double>(), 3.0, 0.05);
  EXPECT_LT(report()["bend"]["max_surface_error_mm"].get<double>(), 0.05);

  // The filled-in field follows the prescribed surface, and inside it bends by the same law.
  const TetMesh mesh = load_tet_mesh(dir_ / "build" / "mesh" / "body.tetmesh");
  const Eigen::VectorXd x = load_array(dir_ / "build" / "targets" / "bend.positions", "positions");
  const MlsBasis basis(mesh.nodes, {false, 1.7 * mesh_quality(mesh).mean_edge_length});
  double surface_error = 0;
  for (Eigen::Index v = 0; v < mesh.surface_to_node.size(); ++v) {
    const Eigen::Vector3d X = mesh.nodes.row(mesh.surface_to_node(v)).transpose();
    surface_error = std::max(surface_error, (basis.at(X, 0).position(x) - bend(X)).norm());
  }
  const Eigen::Vector3d inside(0.045, 0.002, -0.001);
  const double inside_error = (basis.at(inside, 0).position(x) - bend(inside)).norm();
  std::printf("surface target: surface error %.4f mm, centre error %.4f mm\n", surface_error * 1e3, inside_error * 1e3);
  EXPECT_LT(surface_error, 0.05e-3);
  EXPECT_LT(inside_error, 0.2e-3);
}

/// The same bar given as a skin ten times denser (0.6 mm triangles, 24,516 of them) than the mesh's
/// 6 mm edges: the mesh stage remeshes it, and the target, a bent copy of that dense skin, reaches
/// the mesh's nodes through their places on it. It bends the bar as the coarse skin's target does.
TEST_F(TargetsE2E, ASurfaceTargetOnASkinTenTimesDenserThanTheMeshBendsTheSame)
{
  const auto bend = [](const Eigen::Vector3d& X) -> Eigen::Vector3d {
    return X + Eigen::Vector3d(0, 0, 0.05 * X.x() * X.x() / 0.06);
  };
  const SurfaceMesh dense = test::box({0, -0.008, -0.008}, {0.06, 0.008, 0.008}, Eigen::Vector3i(100, 27, 27));
  SurfaceMesh bent = dense;
  for (Eigen::Index v = 0; v < bent.num_vertices(); ++v)
    bent.vertices.row(v) = bend(dense.vertices.row(v).transpose()).transpose();
  write_stl(dir_ / "bar.stl", dense);
  write_stl(dir_ / "bent.stl", bent);
  design("[[target]]\nname = \"bend\"\nkind = \"surface\"\nsurface = \"bent.stl\"\n");
  const auto r = make();
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto mesh_report = nlohmann::json::parse(test::read_text(dir_ / "build" / "mesh" / "report.json"))["mesh"];
  ASSERT_EQ(mesh_report["surface_triangles"]["treatment"], "remesh");
  EXPECT_NEAR(report()["bend"]["max_displacement_mm"].get<double>(), 3.0, 0.05);
  EXPECT_LT(report()["bend"]["max_surface_error_mm"].get<double>(), 0.05);

  const TetMesh mesh = load_tet_mesh(dir_ / "build" / "mesh" / "body.tetmesh");
  EXPECT_LT(mesh.nodes.rows(), dense.num_vertices() / 5);
  const Eigen::VectorXd x = load_array(dir_ / "build" / "targets" / "bend.positions", "positions");
  const MlsBasis basis(mesh.nodes, {false, 1.7 * mesh_quality(mesh).mean_edge_length});
  double surface_error = 0;
  for (Eigen::Index v = 0; v < dense.num_vertices(); ++v) {
    const Eigen::Vector3d X = dense.vertices.row(v).transpose();
    surface_error = std::max(surface_error, (basis.at(X, 0).position(x) - bend(X)).norm());
  }
  const Eigen::Vector3d inside(0.045, 0.002, -0.001);
  const double inside_error = (basis.at(inside, 0).position(x) - bend(inside)).norm();
  std::printf("surface target on a dense skin: %ld nodes for %ld skin vertices; error at the skin's vertices %.4f mm, "
              "inside %.4f mm\n",
              static_cast<long>(mesh.nodes.rows()), static_cast<long>(dense.num_vertices()), surface_error * 1e3,
              inside_error * 1e3);
  EXPECT_LT(surface_error, 0.1e-3);
  EXPECT_LT(inside_error, 0.2e-3);
}

/// On the dense skin, `[[fixed]] vertices` (the 784 at x = 0) hold the nodes at those places: the
/// bar droops under a tip load as it does held by a box around that face.
TEST_F(TargetsE2E, FixedVerticesOfADenseSkinHoldTheNodesAtTheirPlaces)
{
  const SurfaceMesh dense = test::box({0, -0.008, -0.008}, {0.06, 0.008, 0.008}, Eigen::Vector3i(100, 27, 27));
  write_stl(dir_ / "bar.stl", dense);
  std::vector<int> clamp;
  for (Eigen::Index v = 0; v < dense.num_vertices(); ++v)
    if (dense.vertices(v, 0) < 1e-12) clamp.push_back(static_cast<int>(v));
  ASSERT_EQ(clamp.size(), 28u * 28u);
  const std::string droop = "[[target]]\nname = \"droop\"\nkind = \"forces\"\n"
                            "load = [{ box = { min = [59, -9, -9], max = [61, 9, 9] }, force = [0, 0, -0.05] }]\n";
  double tip[2];
  for (int by_vertices = 0; by_vertices < 2; ++by_vertices) {
    std::string text = std::string(kDesign) + droop;
    if (by_vertices) {
      const std::string box = "box = { min = [-1, -9, -9], max = [0.5, 9, 9] }";
      text.replace(text.find(box), box.size(), fmt::format("vertices = [{}]", fmt::join(clamp, ", ")));
    }
    test::write_text(dir_ / "design.toml", text);
    const auto r = make();
    ASSERT_EQ(r.exit_code, 0) << r.err;
    tip[by_vertices] = report()["droop"]["max_displacement_mm"].get<double>();
  }
  std::printf("dense skin, held by a box: %.3f mm; by its 784 vertices at x = 0: %.3f mm\n", tip[0], tip[1]);
  EXPECT_GT(tip[0], 1.0);
  EXPECT_NEAR(tip[1], tip[0], 0.01 * tip[0]);
}

TEST_F(TargetsE2E, SurfaceWithOtherVerticesIsRefused)
{
  write_stl(dir_ / "other.stl", test::box({0, -0.008, -0.008}, {0.06, 0.008, 0.008}, 2));
  design("[[target]]\nname = \"bend\"\nkind = \"surface\"\nsurface = \"other.stl\"\n");
  auto r = make();
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("[target.bend].surface: other.stl has 26 vertices, the body's surface"));

  SurfaceMesh shuffled = bar_; // same vertices, faces in another order: the import order differs
  shuffled.faces = bar_.faces.colwise().reverse();
  write_stl(dir_ / "shuffled.stl", shuffled);
  design("[[target]]\nname = \"bend\"\nkind = \"surface\"\nsurface = \"shuffled.stl\"\n");
  r = make();
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("connects its vertices differently"));
}

/// A pose target curls the bar's end 30° about z along a circular arc (the end face moved to the
/// arc's end and turned with it, about its own centroid): the report gives the angle reached, and
/// the deformed end face itself turned by 30° within 1°.
TEST_F(TargetsE2E, APoseTargetOfAKnownRotationIsReachedWithinADegree)
{
  const double L = 60, theta = 30 * M_PI / 180, R = L / theta; // mm; the arc of a uniform curl
  const Eigen::Vector3d shift(R * std::sin(theta) - L, R * (1 - std::cos(theta)), 0);
  design(fmt::format("[[target]]\nname = \"curl\"\nkind = \"pose\"\n"
                     "pose = [{{ box = {{ min = [59, -9, -9], max = [61, 9, 9] }}, axis = [0, 0, 1], angle_deg = 30, "
                     "translation = [{:.4f}, {:.4f}, 0] }}]\n"
                     "[[tracking_curve]]\nname = \"axis\"\npoints = [[0, 0, 0], [60, 0, 0]]\n",
                     shift.x(), shift.y()));
  const auto r = make();
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto rep = report()["curl"];
  EXPECT_EQ(rep["kind"], "pose");
  EXPECT_LT(rep["max_pose_error_mm"].get<double>(), 0.05);
  const auto& pose = rep["poses"][0];
  EXPECT_EQ(pose["place"], "pose[1]");
  EXPECT_NEAR(pose["asked_rotation_deg"].get<double>(), 30, 1e-9);
  EXPECT_NEAR(pose["rotation_about_asked_axis_deg"].get<double>(), 30, 1.0);
  EXPECT_NEAR(pose["rotation_reached_percent"].get<double>(), 100, 100.0 / 30);
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(pose["translation_mm"][k].get<double>(), pose["asked_translation_mm"][k].get<double>(), 0.1) << k;
  EXPECT_NEAR(pose["asked_translation_mm"][1].get<double>(), shift.y(), 1e-3);
  // The centre line's last point turned with the end (the material's rotation there), its first held.
  const auto& last = rep["poses"][2];
  EXPECT_EQ(last["place"], "axis, last point");
  EXPECT_NEAR(last["rotation_deg"].get<double>(), 30, 2.0);
  EXPECT_LT(rep["poses"][1]["rotation_deg"].get<double>(), 1.0);

  // Independently of the report: the deformed end face's y edge turned by 30° about z.
  const TetMesh mesh = load_tet_mesh(dir_ / "build" / "mesh" / "body.tetmesh");
  const Eigen::VectorXd x = load_array(dir_ / "build" / "targets" / "curl.positions", "positions");
  const MlsBasis basis(mesh.nodes, {false, 1.7 * mesh_quality(mesh).mean_edge_length});
  const Eigen::Vector3d a = basis.at({0.06, -0.008, 0}, 0).position(x), b = basis.at({0.06, 0.008, 0}, 0).position(x);
  const double turned = std::atan2(-(b - a).x(), (b - a).y()) * 180 / M_PI;
  std::printf("pose target: asked 30°, reached %.3f° (report), the end face's edge %.3f°; end moved (%.2f, %.2f) mm of "
              "(%.2f, %.2f)\n",
              pose["rotation_about_asked_axis_deg"].get<double>(), turned, pose["translation_mm"][0].get<double>(),
              pose["translation_mm"][1].get<double>(), shift.x(), shift.y());
  EXPECT_NEAR(turned, 30, 1.0);
}

/// A forces target's report gives the rotation a user would otherwise measure with a script: a
/// torque T about the bar's axis twists its free end by about T L / (G J) (Saint-Venant, a
/// square section: J = 0.1406 a⁴).
TEST_F(TargetsE2E, AForcesTargetReportsTheTwistItsTorqueCauses)
{
  design("[[target]]\nname = \"twist\"\nkind = \"forces\"\n"
         "load = [{ box = { min = [59, -9, -9], max = [61, 9, 9] }, torque = [2e-4, 0, 0] }]\n"
         "[[tracking_curve]]\nname = \"axis\"\npoints = [[0, 0, 0], [60, 0, 0]]\n");
  const auto r = make();
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto rep = report()["twist"];
  const double G = 86.4e3 / (2 * 1.47), J = 0.1406 * std::pow(0.016, 4);
  const double expected = 2e-4 * 0.06 / (G * J) * 180 / M_PI;
  const auto& load = rep["poses"][0];
  EXPECT_EQ(load["place"], "load[1]");
  std::printf("torque 2e-4 N·m: the end region turned %.3f° about (%.3f, %.3f, %.3f), the centre line's end %.3f°; "
              "Saint-Venant %.3f°\n",
              load["rotation_deg"].get<double>(), load["rotation_axis"][0].get<double>(),
              load["rotation_axis"][1].get<double>(), load["rotation_axis"][2].get<double>(),
              rep["poses"][2]["rotation_deg"].get<double>(), expected);
  EXPECT_NEAR(load["rotation_deg"].get<double>(), expected, 0.15 * expected);
  EXPECT_GT(load["rotation_axis"][0].get<double>(), 0.99);
  EXPECT_NEAR(rep["poses"][2]["rotation_deg"].get<double>(), expected, 0.15 * expected);
}

/// `curl_from` instead of a translation worked out by hand: the end is asked to where the arc
/// takes it, (L/θ)(sin θ, 1 − cos θ) − (L, 0) (the test above's), and reaches it.
TEST_F(TargetsE2E, APoseCurledFromTheBaseGoesWhereTheArcTakesIt)
{
  const double L = 60, theta = 30 * M_PI / 180, R = L / theta;
  design("[[target]]\nname = \"curl\"\nkind = \"pose\"\n"
         "pose = [{ box = { min = [59, -9, -9], max = [61, 9, 9] }, axis = [0, 0, 1], angle_deg = 30, "
         "curl_from = [0, 0, 0] }]\n");
  auto r = make();
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto rep = report()["curl"];
  const auto& pose = rep["poses"][0];
  // The end face's nodes: their centroid lies on the bar's axis within 0.05 mm.
  EXPECT_NEAR(pose["asked_translation_mm"][0].get<double>(), R * std::sin(theta) - L, 0.05);
  EXPECT_NEAR(pose["asked_translation_mm"][1].get<double>(), R * (1 - std::cos(theta)), 0.05);
  EXPECT_NEAR(pose["asked_translation_mm"][2].get<double>(), 0, 0.05);
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(pose["translation_mm"][k].get<double>(), pose["asked_translation_mm"][k].get<double>(), 0.1) << k;
  EXPECT_NEAR(pose["rotation_about_asked_axis_deg"].get<double>(), 30, 1.0);

  design("[[target]]\nname = \"curl\"\nkind = \"pose\"\n"
         "pose = [{ box = { min = [59, -9, -9], max = [61, 9, 9] }, angle_deg = 30, curl_from = [0, 0, 0], "
         "translation = [-2.7, 15.35, 0] }]\n");
  r = make();
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("curl_from places the region where a uniform curl takes it: leave out translation"));
  design("[[target]]\nname = \"curl\"\nkind = \"pose\"\n"
         "pose = [{ box = { min = [59, -9, -9], max = [61, 9, 9] }, curl_from = [0, 0, 0] }]\n");
  r = make();
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("curl_from needs the curl's angle"));
  // An angle out of range is refused once, where it is, not also as missing (a new user's 450).
  design("[[target]]\nname = \"curl\"\nkind = \"pose\"\n"
         "pose = [{ box = { min = [59, -9, -9], max = [61, 9, 9] }, angle_deg = 450, curl_from = [0, 0, 0] }]\n");
  r = make();
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("angle_deg"));
  EXPECT_THAT(r.err, Not(HasSubstr("curl_from needs the curl's angle")));
  // A base 9 m away (metres given as mm): the arc sweeps the end 4.7 m; check refuses it as make does.
  design("[[target]]\nname = \"curl\"\nkind = \"pose\"\n"
         "pose = [{ box = { min = [59, -9, -9], max = [61, 9, 9] }, angle_deg = 30, curl_from = [-9000, 0, 0] }]\n"
         "[optimize]\nenabled = false\n");
  for (const auto& run : {test::run_fibermold("check design.toml", dir_.path()), make()}) {
    EXPECT_EQ(run.exit_code, 2);
    EXPECT_THAT(run.err, HasSubstr("no soft body gets there; check `about`, `translation` and `curl_from`"));
  }
}

TEST_F(TargetsE2E, APoseRegionThatIsAlsoHeldIsRefused)
{
  design("[[target]]\nname = \"curl\"\nkind = \"pose\"\n"
         "pose = [{ box = { min = [-1, -9, -9], max = [3, 9, 9] }, axis = [0, 0, 1], angle_deg = 10 }]\n");
  auto r = make();
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("[target.curl].pose[1]"));
  EXPECT_THAT(r.err, HasSubstr("node(s) with [fixed.fixed1]: a node cannot be held in two places"));
  design("[[target]]\nname = \"curl\"\nkind = \"pose\"\npose = [{ box = { min = [59, -9, -9], max = [61, 9, 9] } }]\n");
  r = make();
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("give angle_deg (with axis, about) and/or translation"));
}

/// What the targets stage would refuse of the regions and the target surfaces, `check` refuses
/// first, before any mesh exists: a design `check` passes is not refused by `make` with exit 2.
TEST_F(TargetsE2E, CheckRefusesRegionsAndSurfacesTheTargetsStageWouldRefuse)
{
  const auto check = [&] { return test::run_fibermold("check design.toml", dir_.path()); };
  // Without an optimizer, whose own checks (a tracking curve) would come first.
  const auto design = [&](const std::string& targets) { this->design(targets + "[optimize]\nenabled = false\n"); };
  design("[[target]]\nname = \"curl\"\nkind = \"pose\"\n"
         "pose = [{ box = { min = [70, -9, -9], max = [75, 9, 9] }, axis = [0, 0, 1], angle_deg = 10 }]\n");
  auto r = check();
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(
      r.err,
      HasSubstr("[target.curl].pose[1]: the region selects no node of the mesh: the box (70.0, -9.0, -9.0) mm to "
                "(75.0, 9.0, 9.0) mm misses the body, which spans (0.0, -8.0, -8.0) mm to (60.0, 8.0, 8.0) mm"));
  design("[[target]]\nname = \"droop\"\nkind = \"forces\"\nload = [{ vertices = [9999], force = [0, 0, -0.05] }]\n");
  r = check();
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("[target.droop].load[1]: vertex 9999 does not exist: the surface has"));
  design("[[target]]\nname = \"droop\"\nkind = \"forces\"\nload = [{ point = [30, 0, 20], force = [0, 0, -0.05] }]\n");
  r = check();
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("[target.droop].load[1]: the point (30.0, 0.0, 20.0) mm lies outside the body"));
  write_stl(dir_ / "other.stl", test::box({0, -0.008, -0.008}, {0.06, 0.008, 0.008}, 2));
  design("[[target]]\nname = \"bend\"\nkind = \"surface\"\nsurface = \"other.stl\"\n");
  r = check();
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("[target.bend].surface: other.stl has 26 vertices, the body's surface"));
  design("[[target]]\nname = \"curl\"\nkind = \"pose\"\n"
         "pose = [{ box = { min = [-1, -9, -9], max = [3, 9, 9] }, axis = [0, 0, 1], angle_deg = 10 }]\n");
  r = check();
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(
      r.err,
      ContainsRegex("\\[target.curl\\].pose\\[1\\]: the region shares [0-9]+ surface vertices with \\[fixed.fixed1\\]: "
                    "a node cannot be held in two places"));
  // A translation given in metres instead of mm moves the end 3 m: refused, naming the units.
  design("[[target]]\nname = \"curl\"\nkind = \"pose\"\n"
         "pose = [{ box = { min = [59, -9, -9], max = [61, 9, 9] }, translation = [0, 3000, 0] }]\n");
  r = check();
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err,
              HasSubstr("[target.curl].pose[1]: the pose moves the region up to 3000 mm, more than twice the body's"));
  // Two poses that hold the same vertices.
  design("[[target]]\nname = \"curl\"\nkind = \"pose\"\n"
         "pose = [{ box = { min = [59, -9, -9], max = [61, 9, 9] }, angle_deg = 10 }, { box = { min = [55, -9, -9], "
         "max = [61, 9, 9] }, angle_deg = 5 }]\n");
  r = check();
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, ContainsRegex("\\[target.curl\\].pose\\[2\\]: the region shares [0-9]+ surface vertices with "
                                   "\\[target.curl\\].pose\\[1\\]"));
  // A box between the nodes of the mesh: found by the targets stage, which names the box and the fix.
  design("[[target]]\nname = \"curl\"\nkind = \"pose\"\n"
         "pose = [{ box = { min = [41.1, -9, -9], max = [41.2, 9, 9] }, angle_deg = 10 }]\n");
  r = make();
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("the box (41.1, -9.0, -9.0) mm to (41.2, 9.0, 9.0) mm selects no node of the mesh"));
  EXPECT_THAT(r.err, HasSubstr("widen it to at least the mesh's edge length"));
  // And a design with regions on the body passes.
  design("[[target]]\nname = \"curl\"\nkind = \"pose\"\n"
         "pose = [{ box = { min = [59, -9, -9], max = [61, 9, 9] }, axis = [0, 0, 1], angle_deg = 10 }]\n");
  r = check();
  EXPECT_EQ(r.exit_code, 0) << r.err;
}

TEST_F(TargetsE2E, EditsRerunExactlyTheStagesThatReadThem)
{
  const std::string target = "[[target]]\nname = \"droop\"\nkind = \"forces\"\n"
                             "load = [{ box = { min = [59, -9, -9], max = [61, 9, 9] }, force = [0, 0, -0.05] }]\n";
  design(target);
  ASSERT_EQ(make().exit_code, 0);
  const auto status = [&] { return test::run_fibermold("status design.toml --build-dir build", dir_.path()).out; };
  test::write_text(dir_ / "design.toml",
                   std::string(kDesign).replace(std::string(kDesign).find("wall = 4.0"), 10, "wall = 5.0") + target);
  EXPECT_THAT(status(), HasSubstr("mesh      fresh\ntargets   fresh"));
  design(std::string(target).replace(target.find("-0.05"), 5, "-0.08"));
  EXPECT_THAT(status(), HasSubstr("mesh      fresh\ntargets   stale ([target.droop].load"));
  const auto r = make();
  EXPECT_THAT(r.out, HasSubstr("targets: done"));
  EXPECT_THAT(r.out, HasSubstr("1 stage(s) ran, 1 fresh"));
  // A route's edit: the forces target does not read the fibers (until session 43 it re-ran, and a
  // new user's jaw re-ran its two pose targets, 8 s, at every route edit); a fibers target does.
  const std::string moved = std::string(kDesign).replace(std::string(kDesign).find("[30, 3, 0]"), 10, "[30, 4, 0]");
  const std::string load = std::string(target).replace(target.find("-0.05"), 5, "-0.08");
  test::write_text(dir_ / "design.toml", moved + load);
  EXPECT_THAT(status(), HasSubstr("mesh      fresh\ntargets   fresh"));
  const std::string known = "[[target]]\nname = \"known\"\nkind = \"fibers\"\nfibers = [{ name = \"m1\", "
                            "pressure = 100 }]\n";
  design(load + known);
  ASSERT_EQ(make().exit_code, 0);
  test::write_text(dir_ / "design.toml", moved + load + known);
  EXPECT_THAT(status(), HasSubstr("mesh      fresh\ntargets   stale ([fiber.m1].points"));
}

} // namespace
} // namespace fibermold
