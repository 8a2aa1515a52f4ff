// Distance to a closed surface and inside/outside, against a box where both are known exactly.
#include <gtest/gtest.h>

#include "../primitives.hpp"
#include "mesh/surface_distance.hpp"

namespace fibermold {
namespace {

TEST(SurfaceDistance, BoxDistancesClosestPointsAndSides)
{
  const SurfaceMesh box = test::box({0, 0, 0}, {0.1, 0.02, 0.02}, Eigen::Vector3i(10, 2, 2));
  const SurfaceDistance skin(box.vertices, box.faces);

  const auto centre = skin.closest({0.05, 0.01, 0.01});
  EXPECT_TRUE(centre.inside);
  EXPECT_NEAR(centre.distance, 0.01, 1e-12);

  const auto near_top = skin.closest({0.03, 0.012, 0.019});
  EXPECT_TRUE(near_top.inside);
  EXPECT_NEAR(near_top.distance, 0.001, 1e-12);
  EXPECT_LT((near_top.point - Eigen::Vector3d(0.03, 0.012, 0.02)).norm(), 1e-12);

  const auto outside = skin.closest({0.12, 0.01, 0.01});
  EXPECT_FALSE(outside.inside);
  EXPECT_NEAR(outside.distance, 0.02, 1e-12);
}

} // namespace
} // namespace fibermold
