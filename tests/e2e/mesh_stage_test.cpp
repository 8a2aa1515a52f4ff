// The mesh stage as a user runs it: `fibermold make DESIGN mesh` on good and bad surfaces.
#include <cmath>
#include <cstdint>
#include <random>

#include <fmt/format.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "export/stl_writer.hpp"
#include "mesh/body_mesh.hpp"
#include "mesh/tet_mesh.hpp"
#include "primitives.hpp"
#include "sim/external_forces.hpp"
#include "sim/simulation.hpp"
#include "test_support.hpp"

namespace fibermold {
namespace {

using ::testing::ContainsRegex;
using ::testing::HasSubstr;
namespace fs = std::filesystem;

class MeshStageE2E : public ::testing::Test {
protected:
  /// Writes design.toml naming `surface`, with extra [mesh] lines.
  void design(const std::string& surface, const std::string& mesh = "edge_length = 5.0")
  {
    test::write_text(dir_ / "design.toml",
                     "[design]\nname = \"body\"\nsurface = \"" + surface + "\"\n[mesh]\n" + mesh + "\n");
  }
  test::CommandResult make() { return test::run_fibermold("make design.toml mesh --build-dir build", dir_.path()); }

  /// `make` fails with exit code 2, says `message`, and leaves no mesh outputs.
  void expect_rejected(const std::string& message)
  {
    const auto r = make();
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_THAT(r.err, HasSubstr(message));
    EXPECT_FALSE(fs::exists(dir_ / "build" / "mesh" / "body.vtu"));
    EXPECT_FALSE(fs::exists(dir_ / "build" / ".stamps" / "mesh.json"));
  }

  test::TempDir dir_;
  const SurfaceMesh box_ = test::box({0, 0, 0}, {0.04, 0.02, 0.02}, 4);
};

TEST_F(MeshStageE2E, MeshesABoxAndReportsIt)
{
  write_stl(dir_ / "box.stl", box_);
  design("box.stl");
  const auto r = make();
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const TetMesh mesh = load_tet_mesh(dir_ / "build" / "mesh" / "body.tetmesh");
  EXPECT_NEAR(mesh.volume(), 16e-6, 1e-9 * 16e-6);
  EXPECT_EQ(mesh.surface_to_node.size(), box_.num_vertices());
  const auto report = nlohmann::json::parse(test::read_text(dir_ / "build" / "mesh" / "report.json"));
  EXPECT_NEAR(report["mesh"]["volume_mm3"].get<double>(), 16000.0, 1e-4);
  EXPECT_NEAR(report["mesh"]["volume_mL"].get<double>(), 16.0, 1e-7);
  EXPECT_EQ(report["mesh"]["tets"].get<int>(), mesh.num_tets());
  EXPECT_EQ(report["surface"]["faces"].get<int>(), box_.num_faces());
  EXPECT_GE(report["mesh"]["min_dihedral_deg"].get<double>(), 1.0);
  EXPECT_THAT(test::read_text(dir_ / "build" / "mesh" / "body.vtu"), HasSubstr("<VTKFile type=\"UnstructuredGrid\""));
}

/// A CAD export: a 100 × 15 × 15 mm EcoFlex bar as 12 triangles, meshed at edge_length = 3 with
/// every other mesh option at its default, clamped at x = 0 and hanging under gravity. An
/// independent solver (CalculiX, converged) puts its tip 58.9 mm down. With the input's triangles
/// kept exactly the mesh stage made 8 nodes and 6 tets, and the tip sagged 3.0 mm.
// A number likely written in another unit is warned at its line by check (before its checks) and by
// make, and stops neither: a density of 1.07 (g/cm³) where kg/m³ are read.
TEST_F(MeshStageE2E, ANumberInAnotherUnitIsWarnedByCheckAndMake)
{
  write_stl(dir_ / "box.stl", box_);
  design("box.stl");
  test::write_text(dir_ / "design.toml",
                   test::read_text(dir_ / "design.toml") + "[material]\ndensity = 1.07\n[optimize]\nenabled = false\n");
  const std::string warning = "design.toml:7:11: [material].density: 1.07 kg/m³ is lighter than any silicone";
  const auto checked = test::run_fibermold("check design.toml", dir_.path());
  EXPECT_EQ(checked.exit_code, 0) << checked.err;
  EXPECT_THAT(checked.out, HasSubstr("warning: "));
  EXPECT_THAT(checked.out, HasSubstr(warning));
  EXPECT_THAT(checked.out, HasSubstr("(if this is g/cm³, write 1070)"));
  const auto made = make();
  EXPECT_EQ(made.exit_code, 0) << made.err;
  EXPECT_THAT(made.out + made.err, HasSubstr(warning));
}

TEST_F(MeshStageE2E, ACadBoxOfTwelveTrianglesSagsAsAConvergedSolverSays)
{
  constexpr double kConverged = 58.9e-3;
  write_stl(dir_ / "box.stl", test::box({0, -7.5e-3, -7.5e-3}, {0.1, 7.5e-3, 7.5e-3}, 1));
  ASSERT_EQ(test::box({0, 0, 0}, {1, 1, 1}, 1).num_faces(), 12);
  for (const auto& [basis, tolerance] : {std::pair{"mls-linear", 0.03}, std::pair{"fem-p2", 0.02}}) {
    test::write_text(dir_ / "design.toml",
                     fmt::format("[design]\nname = \"body\"\nsurface = \"box.stl\"\n[mesh]\nedge_length = 3\n"
                                 "[sim]\nbasis = \"{}\"\n",
                                 basis));
    const auto r = make();
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto report = nlohmann::json::parse(test::read_text(dir_ / "build" / "mesh" / "report.json"))["mesh"];
    EXPECT_TRUE(report["surface_triangles"]["split"].get<bool>());
    EXPECT_GT(report["surface_triangles"]["points_added"].get<int>(), 500);
    EXPECT_LT(report["surface_triangles"]["deviation_mm"].get<double>(), 1e-9); // the points lie on the input's faces
    // TetGen's quality refinement on the surface makes the tets finer than the volume bound alone
    // (a mean edge of 2.22 mm, 19,573 tets until session 25): the bound is rescaled to the edge length.
    EXPECT_NEAR(report["edge_length_mm"]["mean"].get<double>(), 3.0, kEdgeLengthTolerance * 3.0);
    EXPECT_GT(report["sizing"]["tetgen_runs"].get<int>(), 1);
    const TetMesh mesh = load_tet_mesh(dir_ / "build" / "mesh" / "body.tetmesh");
    EXPECT_NEAR(mesh.volume(), 22.5e-6, 1e-6 * 22.5e-6);
    SimulationOptions o; // the design file's defaults: EcoFlex, gravity −z
    o.basis = *value_in(kBasisNames, basis);
    o.fixed_nodes = {nodes_in_box(mesh.nodes, {-1e-3, -1, -1}, {1e-9, 1, 1})};
    Simulation sim(mesh, o);
    Eigen::VectorXd x = sim.rest();
    NullProgress progress;
    const NewtonSummary solved = sim.solve(x, progress);
    ASSERT_TRUE(solved.converged) << solved.brief();
    const Eigen::Vector3d tip(0.1, 0, 0);
    const double sag = -(sim.basis().at(tip, 0).position(x) - tip).z();
    std::printf("12-triangle box, %s: %ld nodes, %ld tets, tip %.2f mm down (converged: 58.9 mm, %.1f %%)\n", basis,
                static_cast<long>(mesh.nodes.rows()), static_cast<long>(mesh.num_tets()), sag * 1e3,
                100 * (sag / kConverged - 1));
    EXPECT_NEAR(sag, kConverged, tolerance * kConverged) << basis;
  }
}

/// Kept exactly (surface_triangles = "keep"), the same box meshes into a few slivers, and the mesh
/// stage says so: the quality bounds are missed, and how to meet them.
TEST_F(MeshStageE2E, KeepingLargeTrianglesIsWarnedAbout)
{
  write_stl(dir_ / "box.stl", test::box({0, -7.5e-3, -7.5e-3}, {0.1, 7.5e-3, 7.5e-3}, 1));
  design("box.stl", "edge_length = 3\nsurface_triangles = \"keep\"");
  const auto r = make();
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("exceed the radius-edge ratio bound 1.5"));
  EXPECT_THAT(r.err, HasSubstr("[mesh] surface_triangles = \"split\""));
  const auto report = nlohmann::json::parse(test::read_text(dir_ / "build" / "mesh" / "report.json"))["mesh"];
  EXPECT_FALSE(report["surface_triangles"]["split"].get<bool>());
  EXPECT_EQ(report["surface_triangles"]["points_added"].get<int>(), 0);
  EXPECT_FALSE(report["quality_bounds_met"].get<bool>());
  EXPECT_LT(report["tets"].get<int>(), 50);
}

/// A surface whose triangles are well under the edge length (a 3 mm grid asked for 5.5 mm edges:
/// 0.64×, above auto's 0.5× remeshing threshold) holds the mesh finer than asked when kept. Asked
/// to keep them, the stage says so and how to coarsen it; at "auto" it remeshes the surface to the
/// edge length and says why.
TEST_F(MeshStageE2E, KeptTrianglesFinerThanTheEdgeLengthAreWarnedAboutOrRemeshed)
{
  write_stl(dir_ / "box.stl", test::box({0, 0, 0}, {0.06, 0.012, 0.012}, Eigen::Vector3i(20, 4, 4)));
  design("box.stl", "edge_length = 5.5\nsurface_triangles = \"keep\"");
  auto r = make();
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto report = nlohmann::json::parse(test::read_text(dir_ / "build" / "mesh" / "report.json"))["mesh"];
  ASSERT_EQ(report["surface_triangles"]["treatment"], "keep");
  EXPECT_LT(report["mean_edge_length_mm"].get<double>(), 0.8 * 5.5);
  EXPECT_FALSE(report["sizing"]["mean_edge_within_tolerance"].get<bool>());
  EXPECT_THAT(r.err, HasSubstr("surface: its triangles are kept and their mean edge"));
  EXPECT_THAT(r.err, HasSubstr("surface_triangles = \"remesh\" coarsens it"));
  EXPECT_THAT(r.err, ContainsRegex("mesh: its mean edge, [0-9.]+ mm, is 0\\.[0-9]+× the 5.5 mm asked"));

  design("box.stl", "edge_length = 5.5");
  r = make();
  ASSERT_EQ(r.exit_code, 0) << r.err;
  report = nlohmann::json::parse(test::read_text(dir_ / "build" / "mesh" / "report.json"))["mesh"];
  EXPECT_EQ(report["sizing"]["first_treatment"], "keep");
  EXPECT_EQ(report["surface_triangles"]["treatment"], "remesh");
  EXPECT_NEAR(report["mean_edge_length_mm"].get<double>(), 5.5, kEdgeLengthTolerance * 5.5);
  EXPECT_THAT(
      test::read_text(dir_ / "build" / "logs" / "mesh.log"),
      HasSubstr("with its triangles kept the mesh came out finer than asked (its own vertices hold it); remeshed"));
}

TEST_F(MeshStageE2E, EditingMeshOptionsRerunsTheStage)
{
  write_stl(dir_ / "box.stl", box_);
  design("box.stl");
  ASSERT_EQ(make().exit_code, 0);
  const std::string fresh = test::run_fibermold("status design.toml --build-dir build", dir_.path()).out;
  EXPECT_THAT(fresh, ContainsRegex("mesh +fresh"));
  // Which folder status looked in, whole; and where the default one would be, when there is none.
  EXPECT_THAT(fresh, HasSubstr("build folder " + (fs::canonical(dir_.path()) / "build").string() + "\n"));
  EXPECT_THAT(test::run_fibermold("status design.toml", dir_.path()).out,
              HasSubstr("/out/body: none yet (the default, out/body under the folder you run in; --build-dir names "
                        "another)"));
  design("box.stl", "edge_length = 4.0");
  EXPECT_THAT(test::run_fibermold("status design.toml --build-dir build", dir_.path()).out,
              HasSubstr("stale ([mesh].edge_length changed (5 → 4))"));
  const auto r = make();
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_THAT(r.out, HasSubstr("mesh: done"));
  EXPECT_THAT(make().out, HasSubstr("0 stage(s) ran, 1 fresh"));
}

TEST_F(MeshStageE2E, EmptyFile)
{
  test::write_text(dir_ / "empty.stl", "");
  design("empty.stl");
  expect_rejected("empty.stl: surface file is empty");
}

TEST_F(MeshStageE2E, RandomBytes)
{
  std::mt19937 random(11);
  std::string bytes(10000, '\0');
  for (char& c : bytes) c = static_cast<char>(random());
  test::write_text(dir_ / "noise.stl", bytes);
  design("noise.stl");
  expect_rejected("noise.stl: cannot read the surface");
}

TEST_F(MeshStageE2E, BoxWithOneFaceMissing)
{
  SurfaceMesh s = box_;
  s.faces.conservativeResize(s.num_faces() - 1, 3);
  write_stl(dir_ / "open.stl", s);
  design("open.stl");
  expect_rejected("surface open.stl is not closed: 3 border edges, e.g. at (");
  EXPECT_THAT(make().err, HasSubstr("set [mesh] repair = true"));
}

TEST_F(MeshStageE2E, FlippedFaceFailsThenMeshesWithRepair)
{
  SurfaceMesh s = box_;
  std::swap(s.faces(7, 1), s.faces(7, 2));
  write_stl(dir_ / "flipped.stl", s);
  design("flipped.stl");
  expect_rejected("surface flipped.stl is not consistently oriented: 3 edges where neighbouring faces disagree");
  design("flipped.stl", "edge_length = 5.0\nrepair = true");
  const auto r = make();
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto report = nlohmann::json::parse(test::read_text(dir_ / "build" / "mesh" / "report.json"));
  EXPECT_THAT(report["surface"]["repaired"].dump(), HasSubstr("flipped faces"));
  EXPECT_NEAR(report["mesh"]["volume_mm3"].get<double>(), 16000.0, 1e-4);
}

TEST_F(MeshStageE2E, DuplicatedVerticesMeshWithRepair)
{
  // Each face with its own corners, 1e-5 mm apart from their twins (a few float ulps at 40 mm, below
  // the 1e-6 × diagonal merge tolerance): welding alone cannot close it.
  SurfaceMesh s;
  s.vertices.resize(3 * box_.num_faces(), 3);
  s.faces.resize(box_.num_faces(), 3);
  for (Eigen::Index f = 0; f < box_.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) {
      s.vertices.row(3 * f + k) = box_.vertices.row(box_.faces(f, k)).array() + 1e-8 * (k + 1);
      s.faces(f, k) = static_cast<int>(3 * f + k);
    }
  test::write_obj(dir_ / "dup.obj", s);
  design("dup.obj");
  {
    const auto r = make();
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_THAT(r.err, HasSubstr("is not closed"));
  }
  design("dup.obj", "edge_length = 5.0\nrepair = true");
  const auto r = make();
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto report = nlohmann::json::parse(test::read_text(dir_ / "build" / "mesh" / "report.json"));
  EXPECT_THAT(report["surface"]["repaired"].dump(), HasSubstr("merged"));
  EXPECT_NEAR(report["mesh"]["volume_mm3"].get<double>(), 16000.0, 0.01);
}

TEST_F(MeshStageE2E, AClosedInternalCavityIsRefusedByCheckAndMake)
{
  // A 40 × 20 × 20 mm block with a closed 20 × 8 × 8 mm chamber inside (a PneuNet's, sealed): a
  // valid solid, but a two-part mold cannot cast the void.
  SurfaceMesh chamber = test::box({0.01, 0.006, 0.006}, {0.03, 0.014, 0.014}, 2);
  chamber.faces.col(1).swap(chamber.faces.col(2)); // pointing into the void
  write_stl(dir_ / "hollow.stl", test::combine(box_, chamber));
  design("hollow.stl");
  const std::string message = "surface hollow.stl has a closed internal cavity of 1280 mm³ around (20.0, 10.0, 10.0) "
                              "mm: a two-part mold cannot cast it";
  const auto checked = test::run_fibermold("check design.toml", dir_.path());
  EXPECT_EQ(checked.exit_code, 2) << checked.err;
  EXPECT_THAT(checked.err, HasSubstr(message));
  // Opening it through a small inlet does not make it castable (a new user's 4 × 3 mm inlet into a
  // 65 × 8 × 7 mm chamber): the advice says how wide.
  EXPECT_THAT(checked.err, HasSubstr("open it through the skin toward [mold] pull, as wide as it is across, so that a "
                                     "mold half forms it as a pocket (a narrower inlet, or one to the side, leaves a "
                                     "core that no half can pull out)"));
  expect_rejected(message);
}

TEST_F(MeshStageE2E, NonManifoldEdge)
{
  write_stl(dir_ / "edge.stl", test::combine(test::box({0, 0, 0}, {0.01, 0.01, 0.01}, 1),
                                             test::box({0.01, 0.01, 0}, {0.02, 0.02, 0.01}, 1)));
  design("edge.stl");
  expect_rejected(
      "surface edge.stl is not manifold: 1 edges shared by more than two faces, e.g. at (10.0, 10.0, 5.0) mm");
}

TEST_F(MeshStageE2E, InterpenetratingBoxes)
{
  write_stl(dir_ / "two.stl", test::combine(box_, test::box({0.033, 0.0043, 0.0047}, {0.052, 0.0151, 0.0163}, 2)));
  design("two.stl");
  expect_rejected("surface two.stl intersects itself");
}

TEST_F(MeshStageE2E, NanCoordinates)
{
  SurfaceMesh s = box_;
  s.vertices(2, 2) = std::nan("");
  test::write_obj(dir_ / "nan.obj", s);
  design("nan.obj");
  expect_rejected("nan.obj: 1 vertices have coordinates that are not finite numbers");
}

TEST_F(MeshStageE2E, FlatMesh)
{
  SurfaceMesh s;
  s.vertices.resize(3, 3);
  s.vertices << 0, 0, 0, 0.01, 0, 0, 0, 0.01, 0;
  s.faces.resize(2, 3);
  s.faces << 0, 1, 2, 0, 2, 1;
  write_stl(dir_ / "flat.stl", s);
  design("flat.stl");
  expect_rejected("surface flat.stl encloses no volume: it is flat");
}

TEST_F(MeshStageE2E, MissingFile)
{
  design("nowhere.stl");
  expect_rejected("[design].surface: file not found");
}

TEST_F(MeshStageE2E, UnsupportedExtension)
{
  test::write_text(dir_ / "body.scad", "cube(10);");
  design("body.scad");
  expect_rejected("unsupported surface format '.scad'");
}

TEST_F(MeshStageE2E, WrongUnitsAreRefusedBeforeMeshing)
{
  write_stl(dir_ / "box.stl", box_); // in mm, declared as m: a 40 m box, beyond any robot
  test::write_text(dir_ / "design.toml", "[design]\nsurface = \"box.stl\"\nunits = \"m\"\n[mesh]\nedge_length = 5.0\n");
  expect_rejected(
      "box.stl: the surface spans 4.9e+04 mm corner to corner (0 to 40 in the file's units): a body is between 0.1 mm "
      "and 10 m across; check [design].units");
  // Declared as cm: a 400 mm box, at 2 mm edges about 2e7 tets.
  test::write_text(dir_ / "design.toml",
                   "[design]\nsurface = \"box.stl\"\nunits = \"cm\"\n[mesh]\nedge_length = 2.0\n");
  expect_rejected(
      "design.toml:5:15: [mesh].edge_length: 2 mm for a body of 1.6e+07 mm³ would make about 2.12e+07 tets, more than "
      "[mesh].max_tets = 2000000; raise edge_length, or check [design].units");
}

/// A glTF tetrahedron of edge `a` mm with its geometry in the external buffer tet.bin.
void write_gltf_tetrahedron(const fs::path& dir, float a)
{
  const float p[12] = {0, 0, 0, a, 0, 0, 0, a, 0, 0, 0, a};
  const std::uint16_t idx[12] = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
  std::string bin(reinterpret_cast<const char*>(p), sizeof p);
  bin.append(reinterpret_cast<const char*>(idx), sizeof idx);
  test::write_text(dir / "tet.bin", bin);
  test::write_text(dir / "tet.gltf",
                   fmt::format(R"({{"asset": {{"version": "2.0"}}, "scene": 0, "scenes": [{{"nodes": [0]}}],
 "nodes": [{{"mesh": 0}}], "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0}}, "indices": 1}}]}}],
 "buffers": [{{"uri": "tet.bin", "byteLength": 72}}],
 "bufferViews": [{{"buffer": 0, "byteOffset": 0, "byteLength": 48}},
                 {{"buffer": 0, "byteOffset": 48, "byteLength": 24}}],
 "accessors": [{{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
                 "min": [0, 0, 0], "max": [{0}, {0}, {0}]}},
               {{"bufferView": 1, "componentType": 5123, "count": 12, "type": "SCALAR"}}]}})",
                               a));
}

TEST_F(MeshStageE2E, GltfExternalBufferIsAnInput)
{
  write_gltf_tetrahedron(dir_.path(), 30);
  design("tet.gltf");
  ASSERT_EQ(make().exit_code, 0) << make().err;
  const auto volume = [&] {
    return nlohmann::json::parse(test::read_text(dir_ / "build" / "mesh" / "report.json"))["mesh"]["volume_mm3"]
        .get<double>();
  };
  EXPECT_NEAR(volume(), 30.0 * 30 * 30 / 6, 1e-6);
  write_gltf_tetrahedron(dir_.path(), 40); // only the .bin's content changes
  EXPECT_THAT(test::run_fibermold("status design.toml --build-dir build", dir_.path()).out,
              ContainsRegex("mesh +stale \\(file tet.bin changed"));
  ASSERT_EQ(make().exit_code, 0);
  EXPECT_NEAR(volume(), 40.0 * 40 * 40 / 6, 1e-6);
}

TEST_F(MeshStageE2E, RemeshingIsRefusedBeforeItCouldExhaustMemory)
{
  write_stl(dir_ / "box.stl", box_);
  design("box.stl", "edge_length = 0.01\nsurface_triangles = \"remesh\"");
  expect_rejected("more than [mesh].max_tets");
}

TEST_F(MeshStageE2E, TheOldRemeshKeyNamesItsReplacement)
{
  write_stl(dir_ / "box.stl", box_);
  design("box.stl", "repair = true\nremesh = true");
  expect_rejected("[mesh].remesh: replaced by surface_triangles = \"remesh\"");
}

/// A scan-like skin of the same bar: 0.5 mm triangles (51,600), asked for 3 mm. At "auto" the stage
/// remeshes it to the edge length, and the bar sags as the converged solver says.
TEST_F(MeshStageE2E, ADenseScanCoarsensToTheAskedEdgeLengthAndSagsAsAConvergedSolverSays)
{
  constexpr double kConverged = 58.9e-3;
  const SurfaceMesh scan = test::box({0, -7.5e-3, -7.5e-3}, {0.1, 7.5e-3, 7.5e-3}, Eigen::Vector3i(200, 30, 30));
  write_stl(dir_ / "scan.stl", scan);
  design("scan.stl", "edge_length = 3");
  const auto r = make();
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(test::read_text(dir_ / "build" / "logs" / "mesh.log"), HasSubstr("remeshed to it, 51600 →"));
  const auto report = nlohmann::json::parse(test::read_text(dir_ / "build" / "mesh" / "report.json"))["mesh"];
  const auto& triangles = report["surface_triangles"];
  EXPECT_EQ(triangles["treatment"], "remesh");
  EXPECT_NEAR(triangles["input_mean_edge_mm"].get<double>(), 0.57, 0.01);
  EXPECT_NEAR(triangles["remeshed"]["mean_edge_mm"].get<double>(), 3.0, 0.25 * 3.0);
  EXPECT_LT(triangles["deviation_mm"].get<double>(), 1e-6); // flat faces, sharp edges kept
  EXPECT_EQ(triangles["remeshed"]["input_vertices_off"].get<int>(), 0);
  const double mean = report["edge_length_mm"]["mean"].get<double>();
  std::printf("dense scan: %d → %d faces; mesh mean edge %.2f mm (asked 3)\n",
              triangles["remeshed"]["input_faces"].get<int>(), triangles["remeshed"]["faces"].get<int>(), mean);
  EXPECT_NEAR(mean, 3.0, 0.25 * 3.0);
  const TetMesh mesh = load_tet_mesh(dir_ / "build" / "mesh" / "body.tetmesh");
  EXPECT_LT(mesh.nodes.rows(), scan.num_vertices() / 3);
  EXPECT_EQ(mesh.surface_vertices.rows(), scan.num_vertices()); // the scan as given, for the molds
  EXPECT_NEAR(mesh.volume(), 22.5e-6, 1e-6 * 22.5e-6);

  SimulationOptions o; // the design file's defaults: EcoFlex, gravity −z, mls-linear
  o.fixed_nodes = {nodes_in_box(mesh.nodes, {-1e-3, -1, -1}, {1e-9, 1, 1})};
  Simulation sim(mesh, o);
  Eigen::VectorXd x = sim.rest();
  NullProgress progress;
  ASSERT_TRUE(sim.solve(x, progress).converged);
  const Eigen::Vector3d tip(0.1, 0, 0);
  const double sag = -(sim.basis().at(tip, 0).position(x) - tip).z();
  std::printf("dense scan: tip %.2f mm down (converged: 58.9 mm, %.1f %%)\n", sag * 1e3, 100 * (sag / kConverged - 1));
  EXPECT_NEAR(sag, kConverged, 0.03 * kConverged);
}

/// A smooth bump 3 mm high and 1.5 mm wide on a block's dense top, at 6 mm edges: remeshing cannot
/// keep it, and the stage says where.
TEST_F(MeshStageE2E, AFeatureTheEdgeLengthCannotHoldIsWarnedAboutWhereItIs)
{
  SurfaceMesh s = test::box({0, 0, 0}, {0.04, 0.02, 0.01}, Eigen::Vector3i(80, 40, 20));
  for (Eigen::Index v = 0; v < s.num_vertices(); ++v)
    if (s.vertices(v, 2) > 0.01 - 1e-12)
      s.vertices(v, 2) +=
          0.003 * std::exp(-(std::pow(s.vertices(v, 0) - 0.03, 2) + std::pow(s.vertices(v, 1) - 0.01, 2)) / 4.5e-6);
  write_stl(dir_ / "bumped.stl", s);
  design("bumped.stl", "edge_length = 6");
  const auto r = make();
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err,
              ContainsRegex(
                  "input vertices lie more than 1.5 mm from the mesh's surface \\(up to 2\\.[0-9]+ mm, near "
                  "\\((29|30)\\.[0-9], (9|10)\\.[0-9], 1[23]\\.[0-9]\\) mm\\): features smaller than the edge length"));
  const auto report = nlohmann::json::parse(test::read_text(dir_ / "build" / "mesh" / "report.json"))["mesh"];
  EXPECT_GT(report["surface_triangles"]["remeshed"]["input_vertices_off"].get<int>(), 0);
  EXPECT_GT(report["surface_triangles"]["deviation_mm"].get<double>(), 1.5);
}

TEST_F(MeshStageE2E, RerunWithSameInputsWritesIdenticalOutputs)
{
  write_stl(dir_ / "box.stl", box_);
  design("box.stl");
  ASSERT_EQ(make().exit_code, 0);
  const std::string report = test::read_text(dir_ / "build" / "mesh" / "report.json");
  const std::string vtu = test::read_text(dir_ / "build" / "mesh" / "body.vtu");
  ASSERT_EQ(test::run_fibermold("make design.toml mesh --build-dir build --force", dir_.path()).exit_code, 0);
  EXPECT_EQ(test::read_text(dir_ / "build" / "mesh" / "report.json"), report);
  EXPECT_EQ(test::read_text(dir_ / "build" / "mesh" / "body.vtu"), vtu);
}

TEST_F(MeshStageE2E, CheckReportsTheSurfaceWithoutRunning)
{
  write_stl(dir_ / "box.stl", box_);
  // check answers for the whole make: a body without fibers to optimize would be refused by the
  // optimize stage, so check refuses it (exit 2) unless the optimizer is off.
  design("box.stl");
  auto r = test::run_fibermold("check design.toml", dir_.path());
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_THAT(r.err, HasSubstr("[[fiber]]: nothing to optimize: give at least one fiber"));
  design("box.stl", "edge_length = 5.0\n[optimize]\nenabled = false");
  r = test::run_fibermold("check design.toml", dir_.path());
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("1 component(s), 16000 mm³"));
  // The body's size, where a wrong [design] units shows at once (a new user's cm on a mm file).
  EXPECT_THAT(r.out, HasSubstr("body: 40 × 20 × 20 mm, from (0.0, 0.0, 0.0) mm to (40.0, 20.0, 20.0) mm"));
  EXPECT_FALSE(fs::exists(dir_ / "out"));
}

} // namespace
} // namespace fibermold
