// The parting plane's sense of pull: a gripper-like finger (flat palm, deep slots on its back, the
// muscle near the palm) parted with the grooves opening toward the back leaves the lower half a plate
// under the grooves; opening them toward the palm, the plane sits between the grooves and the slots'
// floors, and both halves are deep. A body where both senses part alike keeps the given one.
#include <gtest/gtest.h>

#include "molds/parting.hpp"
#include "primitives.hpp"

namespace fibermold {
namespace {

constexpr double mm = 1e-3;

/// 115 × 30 × 20 mm of 2.5 mm cubes from the origin, the palm at z = 0; six slots 5 mm wide and
/// 12.5 mm deep in its back, every 15 mm from x = 20 mm.
SurfaceMesh slotted_finger()
{
  return test::voxel_body({0, -15 * mm, 0}, 2.5 * mm, {46, 12, 8}, [](int i, int, int k) {
    const bool slot = i >= 8 && i < 44 && (i - 8) % 6 < 2 && k >= 3;
    return !slot;
  });
}

TEST(PullSense, AFingerWithItsMuscleNearThePalmIsPartedWithTheGroovesOpeningTowardThePalm)
{
  const SurfaceMesh finger = slotted_finger();
  const std::vector<std::vector<Eigen::Vector3d>> fibers{
      {{0, 0, 4 * mm}, {57.5 * mm, 0, 4 * mm}, {115 * mm, 0, 4 * mm}}};
  const double radius = 1.8 * mm;
  const PullSense up = pull_sense(finger, fibers, radius, {0, 0, 1}),
                  down = pull_sense(finger, fibers, radius, {0, 0, -1});
  std::printf(
      "pull +z: plane at z = %.2f mm, shallower half %.2f mm, undercut %.2f mm²; pull -z: z = %.2f mm, %.2f mm, "
      "%.2f mm²\n",
      up.parting.point.z() / mm, up.thinner_half / mm, up.parting.undercut_area / 1e-6, down.parting.point.z() / mm,
      down.thinner_half / mm, down.parting.undercut_area / 1e-6);
  // +z: under the grooves' bottoms, 4 − 1.8 = 2.2 mm, in the middle of [0, 2.2].
  EXPECT_NEAR(up.parting.point.z(), 1.1 * mm, 0.01 * mm);
  EXPECT_NEAR(up.thinner_half, 1.1 * mm, 0.01 * mm);
  // −z: above the grooves' bottoms, 4 + 1.8 = 5.8 mm, and below the slots' floors, 7.5 mm.
  EXPECT_NEAR(down.parting.point.z(), 6.65 * mm, 0.01 * mm);
  EXPECT_NEAR(down.thinner_half, 6.65 * mm, 0.01 * mm);
  EXPECT_NEAR(up.parting.undercut_area, 0, 1e-12);
  EXPECT_NEAR(down.parting.undercut_area, 0, 1e-12);

  const std::vector<PullSense> chosen = choose_pull_sense(finger, fibers, radius, {0, 0, 1}, kUndercutWarning);
  ASSERT_EQ(chosen.size(), 2u);
  EXPECT_NEAR(chosen.front().pull.z(), -1, 1e-12);
  // Given −z to begin with, it stays.
  EXPECT_NEAR(choose_pull_sense(finger, fibers, radius, {0, 0, -1}, kUndercutWarning).front().pull.z(), -1, 1e-12);
}

TEST(PullSense, ABarWithItsMuscleOnTheAxisKeepsThePullAsGiven)
{
  const SurfaceMesh bar = test::box({0, -8 * mm, -8 * mm}, {60 * mm, 8 * mm, 8 * mm});
  const std::vector<std::vector<Eigen::Vector3d>> fibers{{{0, 0, 0}, {60 * mm, 0, 0}}};
  const std::vector<PullSense> chosen = choose_pull_sense(bar, fibers, 1.8 * mm, {0, 0, 1}, kUndercutWarning);
  EXPECT_NEAR(chosen.front().pull.z(), 1, 1e-12);
  EXPECT_NEAR(chosen.front().thinner_half, 3.1 * mm, 0.01 * mm); // the middle of [−8, −1.8] mm
}

} // namespace
} // namespace fibermold
