// The tolerance of the mesh stage's volume check grows with the terms summed: a box of 10⁶ tets far
// from the origin fills its surface to within it, the bound stays far below the volume of one tet,
// and a lost tet is caught.
#include "mesh/volume_tolerance.hpp"

#include <cstdio>

#include <gtest/gtest.h>

#include "primitives.hpp"

namespace fibermold {
namespace {

/// A box of n³ cubes, each cut into six tets around its diagonal (Kuhn), at `lo`.
TetMesh kuhn_box(const Eigen::Vector3d& lo, double size, int n)
{
  TetMesh mesh;
  const int m = n + 1;
  mesh.nodes.resize(static_cast<Eigen::Index>(m) * m * m, 3);
  const auto id = [m](int i, int j, int k) { return (i * m + j) * m + k; };
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j)
      for (int k = 0; k < m; ++k) mesh.nodes.row(id(i, j, k)) = (lo + Eigen::Vector3d(i, j, k) * size / n).transpose();
  // The six paths from corner 000 to 111 along the axes, each a positively oriented tet.
  constexpr int kPaths[6][3] = {{0, 1, 2}, {1, 2, 0}, {2, 0, 1}, {0, 2, 1}, {1, 0, 2}, {2, 1, 0}};
  mesh.tets.resize(6 * static_cast<Eigen::Index>(n) * n * n, 4);
  Eigen::Index t = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k)
        for (const auto& path : kPaths) {
          int c[3] = {i, j, k};
          int corners[4];
          corners[0] = id(c[0], c[1], c[2]);
          for (int s = 0; s < 3; ++s) {
            ++c[path[s]];
            corners[s + 1] = id(c[0], c[1], c[2]);
          }
          mesh.tets.row(t) << corners[0], corners[1], corners[2], corners[3];
          if (mesh.tet_volume(t) < 0) std::swap(mesh.tets(t, 1), mesh.tets(t, 2));
          ++t;
        }
  return mesh;
}

TEST(VolumeTolerance, GrowsWithTheTermsSummedAndCatchesALostTet)
{
  constexpr int n = 55;                     // 998,250 tets
  const Eigen::Vector3d lo(0.7, -0.3, 1.1); // far from the origin: coordinates round at 1e-16 m, not 1e-18
  const double size = 0.1;
  const TetMesh mesh = kuhn_box(lo, size, n);
  ASSERT_EQ(mesh.num_tets(), 998'250);
  const SurfaceMesh surface = test::box(lo, lo + Eigen::Vector3d::Constant(size), 1);
  const double exact = size * size * size;
  const double error = std::abs(mesh.volume() - signed_volume(surface));
  const double tolerance = volume_tolerance(mesh, surface, 0);
  std::printf("10^6 tets: |sum of tets - surface volume| = %.3g of V, tolerance %.3g of V; one tet is %.3g of V\n",
              error / exact, tolerance / exact, 1.0 / static_cast<double>(mesh.num_tets()));
  EXPECT_LE(error, tolerance);
  EXPECT_GT(error, 0);                // the sums do round
  EXPECT_LT(tolerance, 1e-9 * exact); // still far below any tet: a lost tet is 1e-6 of V
  TetMesh lost = mesh;
  lost.tets.conservativeResize(mesh.num_tets() - 1, 4);
  EXPECT_GT(std::abs(lost.volume() - signed_volume(surface)), volume_tolerance(lost, surface, 0));
  // Points off the surface by d widen it by d × the area.
  EXPECT_NEAR(volume_tolerance(mesh, surface, 1e-9) - tolerance, 1e-9 * 6 * size * size, 1e-6 * 1e-9 * 6 * size * size);
}

} // namespace
} // namespace fibermold
