// Remeshing the body's surface to the edge length: a coarse box refined, a dense box and a dense
// sphere coarsened (mean edge within 25 % of the asked one, the shape kept), a sharp notch kept,
// and a smooth bump smaller than the edge length found, where it is, by the deviation measure.
#include <cmath>

#include <gtest/gtest.h>

#include "mesh/surface_check.hpp"
#include "mesh/surface_remesh.hpp"
#include "primitives.hpp"

namespace fibermold {
namespace {

TEST(SurfaceRemesh, ACoarseBoxIsRefinedToTheEdgeLengthWithItsCorners)
{
  const SurfaceMesh s = test::box({0, 0, 0}, {0.02, 0.02, 0.02}, 1);
  RemeshReport report;
  const SurfaceMesh r = remesh_surface(s, 0.004, report);
  EXPECT_TRUE(check_surface(r).ok());
  EXPECT_EQ(report.sharp_edges, 12);
  EXPECT_GT(r.num_faces(), 100);
  EXPECT_NEAR(mean_edge_length(r), 0.004, 0.25 * 0.004);
  EXPECT_NEAR(signed_volume(r), 8e-6, 1e-9 * 8e-6); // sharp edges kept: still the cube
}

TEST(SurfaceRemesh, ADenseBoxCoarsensToTheEdgeLengthAndKeepsItsShape)
{
  // 100 × 15 × 15 mm at 0.5 mm cells (a scan of a bar): 51,600 triangles, asked for 3 mm.
  const SurfaceMesh s = test::box({0, -0.0075, -0.0075}, {0.1, 0.0075, 0.0075}, Eigen::Vector3i(200, 30, 30));
  RemeshReport report;
  const SurfaceMesh r = remesh_surface(s, 0.003, report);
  ASSERT_TRUE(check_surface(r).ok());
  std::printf("dense box: %lld → %lld faces, mean edge %.3f mm (input %.3f mm)\n",
              static_cast<long long>(s.num_faces()), static_cast<long long>(r.num_faces()), mean_edge_length(r) * 1e3,
              mean_edge_length(s) * 1e3);
  EXPECT_NEAR(mean_edge_length(r), 0.003, 0.25 * 0.003);
  EXPECT_LT(r.num_faces(), s.num_faces() / 10);
  EXPECT_NEAR(signed_volume(r), signed_volume(s), 1e-9 * signed_volume(s));
  const SurfaceDeviation d = surface_deviation(s, r, 1e-4);
  EXPECT_LT(d.remeshed_from_input, 1e-9);
  EXPECT_LT(d.input_from_remeshed, 1e-9);
  EXPECT_EQ(d.input_vertices_beyond, 0);
}

TEST(SurfaceRemesh, ADenseSphereCoarsensWithinTheChordError)
{
  // r = 10 mm, 0.3 mm triangles, asked for 3 mm: chords of 3 mm sit h²/8r ≈ 0.11 mm inside.
  const SurfaceMesh s = test::sphere(0.01, 200, 100);
  RemeshReport report;
  const SurfaceMesh r = remesh_surface(s, 0.003, report);
  ASSERT_TRUE(check_surface(r).ok());
  EXPECT_NEAR(mean_edge_length(r), 0.003, 0.25 * 0.003);
  const SurfaceDeviation d = surface_deviation(s, r, 0.75e-3);
  std::printf("dense sphere: %lld → %lld faces, mean edge %.3f mm; input up to %.3f mm from the remeshed surface\n",
              static_cast<long long>(s.num_faces()), static_cast<long long>(r.num_faces()), mean_edge_length(r) * 1e3,
              d.input_from_remeshed * 1e3);
  EXPECT_LT(d.remeshed_from_input, 1e-5);
  EXPECT_LT(d.input_from_remeshed, 0.25e-3);
  EXPECT_EQ(d.input_vertices_beyond, 0);
}

TEST(SurfaceRemesh, ASharpNotchNarrowerThanTheEdgeLengthIsKept)
{
  // A 40 × 20 × 10 mm block of 1 mm cubes with a slot 1 mm wide and 8 mm deep at x = 20 mm,
  // remeshed at 6 mm: the slot's edges are sharp (90°), stay constrained, and the slot stays.
  const SurfaceMesh s =
      test::voxel_body({0, 0, 0}, 1e-3, {40, 20, 10}, [](int i, int j, int) { return !(i == 20 && j >= 12); });
  ASSERT_TRUE(check_surface(s).ok());
  RemeshReport report;
  const SurfaceMesh r = remesh_surface(s, 0.006, report);
  ASSERT_TRUE(check_surface(r).ok());
  EXPECT_LT(r.num_faces(), s.num_faces() / 3);
  EXPECT_NEAR(signed_volume(r), signed_volume(s), 1e-9 * signed_volume(s));
  EXPECT_LT(surface_deviation(s, r, 1e-4).input_from_remeshed, 1e-9);
}

/// A 40 × 20 × 10 mm block, its top (0.5 mm cells) raised by a smooth bump 3 mm high and 1.5 mm
/// wide (σ) at (30, 10) mm: a feature smaller than 6 mm edges with no sharp edge to hold it.
SurfaceMesh bumped_block()
{
  SurfaceMesh s = test::box({0, 0, 0}, {0.04, 0.02, 0.01}, Eigen::Vector3i(80, 40, 20));
  for (Eigen::Index v = 0; v < s.num_vertices(); ++v)
    if (s.vertices(v, 2) > 0.01 - 1e-12) {
      const double r2 = std::pow(s.vertices(v, 0) - 0.03, 2) + std::pow(s.vertices(v, 1) - 0.01, 2);
      s.vertices(v, 2) += 0.003 * std::exp(-r2 / (2 * 0.0015 * 0.0015));
    }
  return s;
}

TEST(SurfaceRemesh, ASmoothBumpSmallerThanTheEdgeLengthIsFoundWhereItIs)
{
  const SurfaceMesh s = bumped_block();
  ASSERT_TRUE(check_surface(s).ok());
  RemeshReport report;
  const SurfaceMesh r = remesh_surface(s, 0.006, report);
  const SurfaceDeviation d = surface_deviation(s, r, 0.25 * 0.006);
  std::printf(
      "bump: input up to %.2f mm from the remeshed surface, at (%.1f, %.1f, %.1f) mm, %lld vertices beyond 1.5 mm\n",
      d.input_from_remeshed * 1e3, d.worst_at.x() * 1e3, d.worst_at.y() * 1e3, d.worst_at.z() * 1e3,
      static_cast<long long>(d.input_vertices_beyond));
  EXPECT_GT(d.input_vertices_beyond, 0);
  EXPECT_NEAR(d.worst_at.x(), 0.03, 1.5e-3);
  EXPECT_NEAR(d.worst_at.y(), 0.01, 1.5e-3);
  // At 1 mm edges the bump is kept.
  const SurfaceMesh fine = remesh_surface(s, 0.001, report);
  EXPECT_EQ(surface_deviation(s, fine, 0.25 * 0.006).input_vertices_beyond, 0);
}

} // namespace
} // namespace fibermold
