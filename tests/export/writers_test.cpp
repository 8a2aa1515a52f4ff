// The mold part writers, read back by an independent reader (assimp's importers, as users' slicers
// would): STL and 3MF keep the shape in millimetres, every facet and the volume. The HTML report
// carries its meshes in millimetres and its tables, escaped.
#include <cstring>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/units.hpp"
#include "export/report_html.hpp"
#include "export/stl_writer.hpp"
#include "export/three_mf_writer.hpp"
#include "mesh/surface_import.hpp"
#include "primitives.hpp"
#include "test_support.hpp"

namespace fibermold {
namespace {

TEST(Writers, ThreeMfReadsBackInMillimetres)
{
  test::TempDir dir;
  const SurfaceMesh part = test::box({0, 0, 0}, {0.040, 0.020, 0.010}, Eigen::Vector3i(4, 2, 1));
  write_3mf(dir / "part.3mf", part, "shot1-lower");
  const SurfaceMesh back = import_surface(dir / "part.3mf", units::mm);
  EXPECT_EQ(back.num_faces(), part.num_faces());
  EXPECT_EQ(back.num_vertices(), part.num_vertices()); // indexed: shared vertices stay shared
  EXPECT_NEAR(signed_volume(back), 40e-3 * 20e-3 * 10e-3, 1e-12);
  EXPECT_NEAR(back.vertices.col(0).maxCoeff(), 0.040, 1e-9);
  for (const auto& entry : std::filesystem::directory_iterator(dir.path()))
    EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos) << entry.path() << " left behind";
}

TEST(Writers, StlReadsBackInMillimetres)
{
  test::TempDir dir;
  const SurfaceMesh part = test::box({0, 0, 0}, {0.040, 0.020, 0.010}, Eigen::Vector3i(4, 2, 1));
  write_stl(dir / "part.stl", part);
  const SurfaceMesh back = import_surface(dir / "part.stl", units::mm);
  EXPECT_EQ(back.num_faces(), part.num_faces());
  EXPECT_NEAR(signed_volume(back), 40e-3 * 20e-3 * 10e-3, 1e-12);
}

/// The bytes of a base64 text.
std::string unbase64(const std::string& text)
{
  const std::string digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  int bits = 0, value = 0;
  for (char c : text) {
    if (c == '=') break;
    value = (value << 6) | static_cast<int>(digits.find(c));
    if ((bits += 6) >= 8) out += static_cast<char>((value >> (bits -= 8)) & 0xFF);
  }
  return out;
}

TEST(Report, PageCarriesTheMeshesInMillimetresAndTheTables)
{
  ReportMesh part{"shot1-lower", test::box({0, 0, 0}, {0.040, 0.020, 0.010}), {0.5F, 0.5F, 0.5F}, true, {0, 0, 0.005}};
  ReportLine fiber{"m1 </script><!--<script>", {{0, 0, 0}, {0.040, 0, 0}}};
  ReportTable table{"Mold parts", {"part", "checks"}, {{"shot1-lower", "passed"}, {"a <b> & c", "FAILED"}}};
  const std::string html = report_html("fibermold: bar", {part}, {fiber}, {table});
  EXPECT_NE(html.find("<title>fibermold: bar</title>"), std::string::npos);
  EXPECT_NE(html.find("<td>shot1-lower</td><td>passed</td>"), std::string::npos);
  EXPECT_NE(html.find("<td>a &lt;b&gt; &amp; c</td>"), std::string::npos);
  EXPECT_EQ(html.find("http"), std::string::npos) << "the page must need no network";
  EXPECT_EQ(html.find("</script>"), html.rfind("</script>")) << "a name ended the script early";

  const auto begin = html.find("const SCENE = ") + 14, end = html.find(";\n", begin);
  const auto scene = nlohmann::json::parse(html.substr(begin, end - begin));
  ASSERT_EQ(scene["meshes"].size(), 1u);
  const std::string positions = unbase64(scene["meshes"][0]["positions"]),
                    indices = unbase64(scene["meshes"][0]["indices"]);
  ASSERT_EQ(positions.size(), static_cast<std::size_t>(part.mesh.num_vertices()) * 3 * sizeof(float));
  ASSERT_EQ(indices.size(), static_cast<std::size_t>(part.mesh.num_faces()) * 3 * sizeof(std::uint32_t));
  std::vector<float> p(positions.size() / sizeof(float));
  std::memcpy(p.data(), positions.data(), positions.size());
  for (Eigen::Index i = 0; i < part.mesh.num_vertices(); ++i) {
    EXPECT_FLOAT_EQ(p[3 * i], static_cast<float>(part.mesh.vertices(i, 0) * 1e3));
    EXPECT_FLOAT_EQ(p[3 * i + 2], static_cast<float>((part.mesh.vertices(i, 2) + 0.005) * 1e3)); // drawn at its offset
  }
  EXPECT_EQ(scene["lines"][0]["name"], fiber.name);
  const std::string line = unbase64(scene["lines"][0]["points"]);
  ASSERT_EQ(line.size(), 6 * sizeof(float));
  float x1 = 0;
  std::memcpy(&x1, line.data() + 3 * sizeof(float), sizeof(float));
  EXPECT_FLOAT_EQ(x1, 40.0F);
}

TEST(Report, PlotAxesAreLabelledAtRoundValues)
{
  // A 63-iteration run: 0, 20, 40, 60 (quarters of the range labelled it 15.75, 31.5, 47.25).
  EXPECT_EQ(nice_ticks(1, 63), (std::vector<double>{20, 40, 60}));
  EXPECT_EQ(nice_ticks(0, 63), (std::vector<double>{0, 20, 40, 60}));
  EXPECT_EQ(nice_ticks(0, 227), (std::vector<double>{0, 50, 100, 150, 200}));
  // Small and negative ranges (the labels print 4 significant figures).
  const std::vector<double> small = nice_ticks(0.05, 0.43);
  ASSERT_EQ(small.size(), 4U);
  EXPECT_DOUBLE_EQ(small[0], 0.1);
  EXPECT_DOUBLE_EQ(small[3], 0.4);
  EXPECT_EQ(nice_ticks(-10, 10), (std::vector<double>{-10, -5, 0, 5, 10}));
  EXPECT_EQ(nice_ticks(3, 3), (std::vector<double>{3})); // no range: the value
  // Iterations are whole: a 3-iteration run at 1, 2, 3 (0.5 apart otherwise).
  EXPECT_EQ(nice_ticks(1, 3), (std::vector<double>{1, 1.5, 2, 2.5, 3}));
  EXPECT_EQ(nice_ticks(1, 3, 4, 1), (std::vector<double>{1, 2, 3}));
}

} // namespace
} // namespace fibermold
