// The muscles' cut lengths and ends: the length inside the body, which end leaves it, and which of
// two such ends takes the supply tube (the one nearest the mount).
#include <gtest/gtest.h>

#include "export/muscle_cut.hpp"
#include "primitives.hpp"

namespace fibermold {
namespace {

/// Points 0.1 mm apart along the polyline through `corners`.
std::vector<Eigen::Vector3d> dense(const std::vector<Eigen::Vector3d>& corners)
{
  std::vector<Eigen::Vector3d> out{corners.front()};
  for (std::size_t i = 1; i < corners.size(); ++i) {
    const int n = static_cast<int>(std::ceil((corners[i] - corners[i - 1]).norm() / 0.1e-3));
    for (int k = 1; k <= n; ++k) out.push_back(corners[i - 1] + (corners[i] - corners[i - 1]) * k / n);
  }
  return out;
}

class MuscleCutTest : public ::testing::Test {
protected:
  // A 60 × 16 × 16 mm bar from x = 0; the groove reaches 1.8 mm.
  SurfaceMesh bar_ = test::box({0, -8e-3, -8e-3}, {60e-3, 8e-3, 8e-3});
  SurfaceDistance skin_{bar_.vertices, bar_.faces};
  static constexpr double kReach = 1.8e-3;
};

TEST_F(MuscleCutTest, AFiberFromEndFaceToEndFaceIsCutToTheBodysLengthAndFedNearTheMount)
{
  const MuscleCut cut =
      muscle_cut("m1", dense({{0, 0, 0}, {30e-3, 0, 4e-3}, {60e-3, 0, 0}}), skin_, kReach, Eigen::Vector3d(0, 0, 0));
  const double length = 2 * std::hypot(30e-3, 4e-3);
  EXPECT_NEAR(cut.length, length, 1e-9);
  EXPECT_NEAR(cut.length_inside, length, 0.2e-3); // the end samples sit on the skin
  EXPECT_TRUE(cut.start.leaves_body);
  EXPECT_TRUE(cut.end.leaves_body);
  ASSERT_TRUE(cut.supply);
  EXPECT_EQ(*cut.supply, 0);
  // Mounted at the far end instead: the supply tube goes there.
  EXPECT_EQ(*muscle_cut("m1", dense({{0, 0, 0}, {60e-3, 0, 0}}), skin_, kReach, Eigen::Vector3d(60e-3, 0, 0)).supply,
            1);
}

TEST_F(MuscleCutTest, AFiberPokingOutOfTheSideCountsOnlyItsLengthInside)
{
  // 10 mm of it run outside the bar's side face y = 8 mm.
  const MuscleCut cut =
      muscle_cut("m1", dense({{0, 0, 0}, {40e-3, 0, 0}, {40e-3, 18e-3, 0}}), skin_, kReach, std::nullopt);
  EXPECT_NEAR(cut.length, 58e-3, 1e-9);
  EXPECT_NEAR(cut.length_inside, 48e-3, 0.2e-3);
  EXPECT_FALSE(cut.end.leaves_body); // 10 mm out
  EXPECT_EQ(cut.supply, 0);
}

TEST_F(MuscleCutTest, AnEndBuriedInTheBodyIsSealedAndABuriedFiberHasNoSupplyEnd)
{
  const MuscleCut one = muscle_cut("m1", dense({{0, 0, 0}, {40e-3, 0, 0}}), skin_, kReach, std::nullopt);
  EXPECT_FALSE(one.end.leaves_body); // 8 mm from every face
  EXPECT_EQ(one.supply, 0);
  EXPECT_NEAR((one.start.skin_point - Eigen::Vector3d::Zero()).norm(), 0, 1e-9);
  const MuscleCut buried = muscle_cut("m2", dense({{10e-3, 0, 0}, {50e-3, 0, 0}}), skin_, kReach, std::nullopt);
  EXPECT_FALSE(buried.supply);
  EXPECT_NEAR(buried.length_inside, 40e-3, 1e-9);
}

} // namespace
} // namespace fibermold
