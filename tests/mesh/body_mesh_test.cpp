// The mesh made at the edge length asked (mean tet edge within kEdgeLengthTolerance) whatever the
// surface: a CAD export of a few large triangles (split), a dense scan (remeshed), a surface kept,
// and one whose own vertices would hold a split mesh finer than asked (remeshed instead); and the
// tet estimate that max_tets and check use, against the tets made.
#include "mesh/body_mesh.hpp"

#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "mesh/mesh_quality.hpp"
#include "primitives.hpp"

namespace fibermold {
namespace {

struct Made {
  BodyMesh body;
  double mean_edge_ratio; ///< mean tet edge / edge length asked
  double estimate_ratio;  ///< tets made / expected_tets
};

Made made(const char* name, const SurfaceMesh& surface, SurfaceTriangles policy, double edge)
{
  NullProgress progress;
  Made m{mesh_body(surface, policy, {edge, 1.5, 10, false, true}, progress), 0, 0};
  m.mean_edge_ratio = mean_edge_length(m.body.mesh) / edge;
  const double expected = expected_tets(m.body.mesh.volume(), edge, policy, surface);
  m.estimate_ratio = static_cast<double>(m.body.mesh.num_tets()) / expected;
  std::printf("%s: %s, %ld tets, mean edge %.3f x asked, %d TetGen runs (bound %.3g x), %.2f x the estimate\n", name,
              std::string(choice_name(m.body.surface.treatment)).c_str(), static_cast<long>(m.body.mesh.num_tets()),
              m.mean_edge_ratio, m.body.sizing.tetgen_runs, m.body.sizing.volume_bound_factor, m.estimate_ratio);
  return m;
}

/// A CAD export: the 100 × 15 × 15 mm bar as 12 triangles at 3 mm. At TetGen's volume bound for a
/// 3 mm tet alone it made a mean edge of 2.22 mm (0.74 ×) and 2.31 × the tets the old estimate said.
TEST(BodyMesh, ACadBoxOfTwelveTrianglesIsSplitToTheEdgeLengthAsked)
{
  const Made m = made("12-triangle box", test::box({0, -7.5e-3, -7.5e-3}, {0.1, 7.5e-3, 7.5e-3}, 1),
                      SurfaceTriangles::automatic, 3e-3);
  EXPECT_EQ(m.body.surface.treatment, SurfaceTriangles::split);
  EXPECT_NEAR(m.mean_edge_ratio, 1, kEdgeLengthAim);
  EXPECT_GT(m.body.sizing.tetgen_runs, 1);
  EXPECT_NEAR(m.body.mesh.volume(), 22.5e-6, 1e-9 * 22.5e-6);
  EXPECT_NEAR(m.estimate_ratio, 1, 0.25);
  // Asked to split, the same.
  EXPECT_NEAR(made("12-triangle box, split", test::box({0, 0, 0}, {0.06, 0.04, 0.03}, 1), SurfaceTriangles::split, 4e-3)
                  .mean_edge_ratio,
              1, kEdgeLengthAim);
}

/// A scan-like skin: the bar as 0.5 mm triangles (51,600), remeshed to 3 mm.
TEST(BodyMesh, ADenseScanIsRemeshedToTheEdgeLengthAsked)
{
  const SurfaceMesh scan = test::box({0, -7.5e-3, -7.5e-3}, {0.1, 7.5e-3, 7.5e-3}, Eigen::Vector3i(200, 30, 30));
  const Made m = made("dense scan", scan, SurfaceTriangles::automatic, 3e-3);
  EXPECT_EQ(m.body.surface.treatment, SurfaceTriangles::remesh);
  EXPECT_NEAR(m.mean_edge_ratio, 1, kEdgeLengthTolerance);
  EXPECT_NEAR(m.estimate_ratio, 1, 0.25);
  // A smooth one: a 50 mm sphere of 0.5 mm triangles.
  const Made sphere = made("dense sphere", test::sphere(0.025, 300, 150), SurfaceTriangles::automatic, 3e-3);
  EXPECT_EQ(sphere.body.surface.treatment, SurfaceTriangles::remesh);
  EXPECT_NEAR(sphere.mean_edge_ratio, 1, kEdgeLengthTolerance);
  EXPECT_NEAR(sphere.estimate_ratio, 1, 0.25);
}

/// Triangles made for the edge length are kept, and the estimate follows their size: a 4 mm grid
/// at 4 mm and at 5 mm edges; a 6 mm grid at 5 mm makes a mesh coarser than asked, and the volume
/// bound is rescaled.
TEST(BodyMesh, KeptTrianglesMeshAtTheEdgeLengthAskedAndTheEstimateFollowsThem)
{
  for (const auto& [cells, edge] :
       {std::pair{Eigen::Vector3i(15, 5, 5), 4e-3}, std::pair{Eigen::Vector3i(15, 5, 5), 5e-3},
        std::pair{Eigen::Vector3i(10, 3, 3), 5e-3}}) {
    const Made m =
        made("kept grid", test::box({0, 0, 0}, {0.06, 0.02, 0.02}, cells), SurfaceTriangles::automatic, edge);
    EXPECT_EQ(m.body.surface.treatment, SurfaceTriangles::keep);
    EXPECT_NEAR(m.mean_edge_ratio, 1, kEdgeLengthTolerance);
    EXPECT_NEAR(m.estimate_ratio, 1, 0.25);
  }
}

/// A strip whose long sides are 0.5 mm apart along it and 7.5 mm across: its long triangles would
/// make TetGen split them, but its 1,610 vertices, all kept when split, hold the mesh finer than
/// asked however large the volume bound (0.54 × at 3 mm); a surface of 3 mm triangles would have
/// about 830. At "auto" it is remeshed, and comes to the edge length.
TEST(BodyMesh, ASurfaceWhoseVerticesWouldHoldASplitMeshFineIsRemeshed)
{
  const SurfaceMesh strip = test::box({0, 0, 0}, {0.1, 0.015, 0.015}, Eigen::Vector3i(200, 2, 2));
  const Made split = made("strip, split", strip, SurfaceTriangles::split, 3e-3);
  EXPECT_LT(split.mean_edge_ratio, 1 - kEdgeLengthTolerance);
  const Made m = made("strip, auto", strip, SurfaceTriangles::automatic, 3e-3);
  EXPECT_EQ(m.body.surface.treatment, SurfaceTriangles::remesh);
  EXPECT_NEAR(m.mean_edge_ratio, 1, kEdgeLengthTolerance);
  EXPECT_NEAR(m.estimate_ratio, 1, 0.25);
  EXPECT_NEAR(m.body.mesh.volume(), 22.5e-6, 1e-9 * 22.5e-6);
  EXPECT_EQ(m.body.mesh.surface_to_node.size(),
            static_cast<std::size_t>(strip.num_vertices())); // attached to the input
}

/// A genus-1 CAD-like body (a torus of 576 flat facets) split at 3 mm: meshed, its volume the
/// facets' to round-off and the added points' distance, at the edge length asked.
TEST(BodyMesh, AGenusOneBodyOfLargeFacetsIsMeshedAtTheEdgeLengthAsked)
{
  const SurfaceMesh torus = test::torus(0.04, 0.012, 24, 12);
  const Made m = made("faceted torus", torus, SurfaceTriangles::automatic, 3e-3);
  EXPECT_EQ(m.body.surface.treatment, SurfaceTriangles::split);
  EXPECT_NEAR(m.mean_edge_ratio, 1, kEdgeLengthTolerance);
  EXPECT_NEAR(m.estimate_ratio, 1, 0.25);
  EXPECT_NEAR(m.body.mesh.volume(), signed_volume(torus), 1e-9 * signed_volume(torus));
}

} // namespace
} // namespace fibermold
