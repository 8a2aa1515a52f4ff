#include "mesh/surface_repair.hpp"

#include <functional>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/input_error.hpp"
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

/// `s` without the faces `drop` says to leave out.
SurfaceMesh without_faces(const SurfaceMesh& s, const std::function<bool(Eigen::Index)>& drop)
{
  SurfaceMesh out = s;
  Eigen::Index kept = 0;
  for (Eigen::Index f = 0; f < s.num_faces(); ++f)
    if (!drop(f)) out.faces.row(kept++) = s.faces.row(f);
  out.faces.conservativeResize(kept, 3);
  return out;
}

TEST(SurfaceRepair, AMissingTriangleIsFilledAndTheVolumeRestored)
{
  // A new user's export had dropped one triangle: check said repair fixes it, and repair did not.
  const SurfaceMesh box = test::box(kLo, kHi, 2);
  const SurfaceMesh holed = without_faces(box, [](Eigen::Index f) { return f == 7; });
  ASSERT_FALSE(check_surface(holed).ok());
  RepairReport report;
  const SurfaceCheck c = check_surface(repair_surface(holed, {}, report));
  EXPECT_TRUE(c.ok());
  EXPECT_NEAR(c.volume, 2e-6, 1e-15); // the box's own: its missing face was flat with its neighbours
  EXPECT_EQ(report.filled_holes, 1u);
  EXPECT_EQ(report.hole_faces, 1u);
  EXPECT_THAT(report.changes(), Contains("filled 1 hole(s) of at most 12 edges with 1 faces"));
}

TEST(SurfaceRepair, AStrayTriangleIsNotMadeAPillow)
{
  // A closed box and, beside it, a lone triangle: its 3-edge border bounds the whole piece. Filled, it
  // would be a flat two-sided piece; left, the check says the surface is not closed.
  SurfaceMesh s = test::box(kLo, kHi, 2);
  const Eigen::Index n = s.num_vertices();
  s.vertices.conservativeResize(n + 3, 3);
  s.vertices.row(n) << 0.03, 0, 0;
  s.vertices.row(n + 1) << 0.04, 0, 0;
  s.vertices.row(n + 2) << 0.03, 0.01, 0;
  s.faces.conservativeResize(s.num_faces() + 1, 3);
  s.faces.row(s.num_faces() - 1) << static_cast<int>(n), static_cast<int>(n + 1), static_cast<int>(n + 2);
  RepairReport report;
  const SurfaceCheck c = check_surface(repair_surface(s, {}, report));
  EXPECT_EQ(report.filled_holes, 0u);
  EXPECT_FALSE(c.ok());
}

TEST(SurfaceRepair, AMissingCapIsLeftForItsAuthorAndTheMessageSaysWhy)
{
  // The cap above z = 0.7 r of a sphere: a hole bounded by more than 12 edges, a missing part.
  const SurfaceMesh sphere = test::sphere(0.01);
  const SurfaceMesh holed = without_faces(sphere, [&](Eigen::Index f) {
    double z = 0;
    for (int k = 0; k < 3; ++k) z += sphere.vertices(sphere.faces(f, k), 2) / 3;
    return z > 0.007;
  });
  RepairReport report;
  const SurfaceMesh r = repair_surface(holed, {}, report);
  EXPECT_EQ(report.filled_holes, 0u);
  const SurfaceCheck c = check_surface(r);
  ASSERT_FALSE(c.ok());
  try {
    require_valid_surface(c, r, true);
    FAIL() << "a surface with a hole was accepted";
  } catch (const InputError& e) {
    EXPECT_THAT(std::string(e.what()), ::testing::HasSubstr("is not closed"));
    EXPECT_THAT(std::string(e.what()),
                ::testing::HasSubstr("repair could not fix it (it stitches gaps narrower than 1e-6 of the body's size "
                                     "and fills holes of up to 12 edges), fix it in a mesh editor"));
  }
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
