#include "mesh/surface_check.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/input_error.hpp"
#include "primitives.hpp"

namespace fibermold {
namespace {

using ::testing::HasSubstr;

const Eigen::Vector3d kLo(0, 0, 0), kHi(0.02, 0.01, 0.01);

/// The one problem found in `s`.
SurfaceProblem only_problem(const SurfaceMesh& s)
{
  const SurfaceCheck c = check_surface(s);
  EXPECT_EQ(c.problems.size(), 1u);
  return c.problems.empty() ? SurfaceProblem{} : c.problems.front();
}

TEST(SurfaceCheck, PrimitivesAreValidSolidsWithTheirVolume)
{
  const SurfaceCheck b = check_surface(test::box(kLo, kHi, 3));
  EXPECT_TRUE(b.ok());
  EXPECT_NEAR(b.volume, 2e-6, 1e-18);
  EXPECT_EQ(b.components, 1);
  EXPECT_TRUE(b.warnings.empty());
  for (const SurfaceMesh& s : {test::cylinder(0.01, 0.05), test::sphere(0.02), test::torus(0.03, 0.01)}) {
    const SurfaceCheck c = check_surface(s);
    EXPECT_TRUE(c.ok()) << c.problems.front().message;
    EXPECT_GT(c.volume, 0);
  }
  // A 24-gon prism holds (24/2π)·sin(2π/24) of the circle's area.
  EXPECT_NEAR(check_surface(test::cylinder(0.01, 0.05)).volume, 12 * std::sin(2 * M_PI / 24) * 1e-4 * 0.05, 1e-15);
}

TEST(SurfaceCheck, MissingFaceIsABorder)
{
  SurfaceMesh s = test::box(kLo, kHi, 1);
  s.faces.conservativeResize(s.num_faces() - 1, 3);
  const SurfaceProblem p = only_problem(s);
  EXPECT_EQ(p.message, "is not closed: 3 border edges");
  EXPECT_TRUE(p.repairable);
}

TEST(SurfaceCheck, FlippedFaceIsInconsistentOrientation)
{
  SurfaceMesh s = test::box(kLo, kHi, 2);
  std::swap(s.faces(5, 1), s.faces(5, 2));
  const SurfaceProblem p = only_problem(s);
  EXPECT_EQ(p.message, "is not consistently oriented: 3 edges where neighbouring faces disagree");
  EXPECT_TRUE(p.repairable);
}

TEST(SurfaceCheck, InsideOutSurfaceHasNegativeVolume)
{
  SurfaceMesh s = test::sphere(0.01);
  s.faces.col(1).swap(s.faces.col(2));
  const SurfaceProblem p = only_problem(s);
  EXPECT_THAT(p.message, HasSubstr("is oriented inward"));
  EXPECT_TRUE(p.repairable);
}

TEST(SurfaceCheck, BoxesSharingAnEdgeAreNotManifold)
{
  SurfaceMesh a = test::box({0, 0, 0}, {0.01, 0.01, 0.01}, 1);
  SurfaceMesh b = test::box({0.01, 0.01, 0}, {0.02, 0.02, 0.01}, 1);
  // Weld b's vertices onto a's where they coincide, as an importer does.
  SurfaceMesh s = test::combine(a, b);
  for (Eigen::Index v = a.num_vertices(); v < s.num_vertices(); ++v)
    for (Eigen::Index w = 0; w < a.num_vertices(); ++w)
      if (s.vertices.row(v) == s.vertices.row(w))
        for (Eigen::Index f = 0; f < s.num_faces(); ++f)
          for (int k = 0; k < 3; ++k)
            if (s.faces(f, k) == v) s.faces(f, k) = static_cast<int>(w);
  const SurfaceCheck c = check_surface(s);
  ASSERT_FALSE(c.ok());
  EXPECT_THAT(c.problems.front().message, HasSubstr("is not manifold: 1 edges shared by more than two faces"));
  EXPECT_FALSE(c.problems.front().repairable);
  EXPECT_DOUBLE_EQ(c.problems.front().where.x(), 0.01);
  EXPECT_DOUBLE_EQ(c.problems.front().where.y(), 0.01);
}

TEST(SurfaceCheck, InterpenetratingBoxesIntersect)
{
  const SurfaceMesh s = test::combine(test::box({0, 0, 0}, {0.02, 0.02, 0.02}, 2),
                                      test::box({0.01, 0.005, 0.005}, {0.03, 0.015, 0.015}, 2));
  const SurfaceProblem p = only_problem(s);
  EXPECT_THAT(p.message, HasSubstr("intersects itself"));
  EXPECT_FALSE(p.repairable);
  EXPECT_EQ(check_surface(s).components, 2);
}

TEST(SurfaceCheck, FlatSurfaceEnclosesNoVolume)
{
  // A triangle, both sides: closed and consistently oriented, but flat.
  SurfaceMesh s;
  s.vertices.resize(3, 3);
  s.vertices << 0, 0, 0, 0.01, 0, 0, 0, 0.01, 0;
  s.faces.resize(2, 3);
  s.faces << 0, 1, 2, 0, 2, 1;
  const SurfaceCheck c = check_surface(s);
  ASSERT_FALSE(c.ok());
  EXPECT_THAT(c.problems.back().message, HasSubstr("encloses no volume"));
}

TEST(SurfaceCheck, DegenerateFacesAndUnusedVertices)
{
  SurfaceMesh s = test::box(kLo, kHi, 1);
  s.vertices.conservativeResize(s.num_vertices() + 1, 3);
  s.vertices.row(s.num_vertices() - 1) << 1, 1, 1;
  const SurfaceProblem p = only_problem(s);
  EXPECT_EQ(p.message, "has 1 vertices that no face uses");

  SurfaceMesh d = test::box(kLo, kHi, 1);
  d.faces(0, 2) = d.faces(0, 1);
  const SurfaceCheck c = check_surface(d);
  EXPECT_EQ(c.problems.front().message, "has 1 degenerate (zero-area) faces");
}

SurfaceMesh hollow_sphere(bool inner_inward)
{
  SurfaceMesh inner = test::sphere(0.01);
  if (inner_inward) inner.faces.col(1).swap(inner.faces.col(2));
  return test::combine(test::sphere(0.02), inner);
}

TEST(SurfaceCheck, HollowBodyWithInwardCavityIsValid)
{
  const SurfaceCheck c = check_surface(hollow_sphere(true));
  EXPECT_TRUE(c.ok()) << c.problems.front().message;
  EXPECT_NEAR(c.volume, signed_volume(test::sphere(0.02)) - signed_volume(test::sphere(0.01)), 1e-15);
  ASSERT_EQ(c.cavities.size(), 1u);
  EXPECT_NEAR(c.cavities[0].volume, signed_volume(test::sphere(0.01)), 1e-15);
  EXPECT_LT(c.cavities[0].centre.norm(), 1e-4);
}

TEST(SurfaceCheck, CavityShellPointingOutwardIsRepairable)
{
  const SurfaceMesh s = hollow_sphere(false);
  const SurfaceProblem p = only_problem(s);
  EXPECT_THAT(p.message, HasSubstr("has shells that point the wrong way"));
  EXPECT_TRUE(p.repairable);
}

TEST(SurfaceCheck, SizeSuggestingWrongUnitsIsAWarning)
{
  EXPECT_THAT(check_surface(test::box({0, 0, 0}, {5e-4, 5e-4, 5e-4})).warnings.front(), HasSubstr("0.5 mm across"));
  EXPECT_THAT(check_surface(test::box({0, 0, 0}, {3, 1, 1})).warnings.front(), HasSubstr("3000 mm across"));
}

TEST(SurfaceCheck, ErrorMessageNamesFileCountLocationAndRepair)
{
  SurfaceMesh s = test::box({0, 0, 0}, {0.024, 0.012, 0.012}, 2);
  s.source = "/somewhere/bar.stl";
  s.faces.conservativeResize(s.num_faces() - 1, 3);
  try {
    require_valid_surface(check_surface(s), s, false);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("/somewhere/bar.stl: surface bar.stl is not closed: 3 border edges, e.g. at ("));
    EXPECT_THAT(e.what(), HasSubstr(") mm; set [mesh] repair = true to fix it"));
  }
}

} // namespace
} // namespace fibermold
