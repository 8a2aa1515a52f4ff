// The mold part writers, read back by an independent reader (assimp's importers, as users' slicers
// would): STL and 3MF keep the shape in millimetres, every facet and the volume.
#include <gtest/gtest.h>

#include "core/units.hpp"
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
  EXPECT_EQ(back.num_vertices(), part.num_vertices());  // indexed: shared vertices stay shared
  EXPECT_NEAR(signed_volume(back), 40e-3 * 20e-3 * 10e-3, 1e-12);
  EXPECT_NEAR(back.vertices.col(0).maxCoeff(), 0.040, 1e-9);
  EXPECT_FALSE(std::filesystem::exists(dir / "part.3mf.tmp"));
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

} // namespace
} // namespace fibermold
