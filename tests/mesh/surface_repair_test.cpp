#include "mesh/surface_repair.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "mesh/surface_check.hpp"
#include "primitives.hpp"

namespace fibermold {
namespace {

using ::testing::Contains;

const Eigen::Vector3d kLo(0, 0, 0), kHi(0.02, 0.01, 0.01);

TEST(SurfaceRepair, FlippedFaceIsTurnedBack)
{
  SurfaceMesh s = test::box(kLo, kHi, 2);
  std::swap(s.faces(5, 1), s.faces(5, 2));
  ASSERT_FALSE(check_surface(s).ok());
  RepairReport report;
  const SurfaceMesh r = repair_surface(s, {}, report);
  const SurfaceCheck c = check_surface(r);
  EXPECT_TRUE(c.ok());
  EXPECT_NEAR(c.volume, 2e-6, 1e-15);
  EXPECT_TRUE(report.reoriented);
  EXPECT_THAT(report.changes(), Contains("flipped faces to agree with their neighbours"));
}

TEST(SurfaceRepair, NearlyDuplicatedVerticesAreMerged)
{
  // Every face gets its own copy of its corners, moved by up to 1e-9 m: a border everywhere.
  const SurfaceMesh box = test::box(kLo, kHi, 2);
  SurfaceMesh s;
  s.vertices.resize(3 * box.num_faces(), 3);
  s.faces.resize(box.num_faces(), 3);
  for (Eigen::Index f = 0; f < box.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) {
      s.vertices.row(3 * f + k) = box.vertices.row(box.faces(f, k)).array() + 1e-9 * ((f + k) % 3);
      s.faces(f, k) = static_cast<int>(3 * f + k);
    }
  ASSERT_FALSE(check_surface(s).ok());
  RepairReport report;
  const SurfaceMesh r = repair_surface(s, {}, report);
  EXPECT_TRUE(check_surface(r).ok());
  EXPECT_EQ(r.num_vertices(), box.num_vertices());
  EXPECT_EQ(report.merged_vertices, static_cast<std::size_t>(3 * box.num_faces() - box.num_vertices()));
}

TEST(SurfaceRepair, InsideOutIsTurnedOutward)
{
  SurfaceMesh s = test::sphere(0.01);
  s.faces.col(1).swap(s.faces.col(2));
  RepairReport report;
  const SurfaceCheck c = check_surface(repair_surface(s, {}, report));
  EXPECT_TRUE(c.ok());
  EXPECT_GT(c.volume, 0);
  EXPECT_TRUE(report.turned_outward);
}

TEST(SurfaceRepair, CavityShellIsTurnedInward)
{
  const SurfaceMesh s = test::combine(test::sphere(0.02), test::sphere(0.01)); // both outward: wrong
  RepairReport report;
  const SurfaceCheck c = check_surface(repair_surface(s, {}, report));
  EXPECT_TRUE(c.ok());
  EXPECT_TRUE(report.turned_outward);
  EXPECT_NEAR(c.volume, signed_volume(test::sphere(0.02)) - signed_volume(test::sphere(0.01)), 1e-15);
}

TEST(SurfaceRepair, ValidSurfaceIsLeftAsIs)
{
  const SurfaceMesh s = test::torus(0.03, 0.01);
  RepairReport report;
  const SurfaceMesh r = repair_surface(s, {}, report);
  EXPECT_TRUE(report.changes().empty());
  EXPECT_EQ(r.num_faces(), s.num_faces());
  EXPECT_NEAR(signed_volume(r), signed_volume(s), 1e-15);
}

} // namespace
} // namespace fibermold
