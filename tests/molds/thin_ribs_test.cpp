// Thin deep ribs: a gripper-like finger with narrow slots in its back, parted between its palm and
// the slots' floors, has a rib of the half that holds its back standing in each slot, as thick as
// the slot is wide and as deep; with slots twice as wide (thicker than kThinRib) none is thin.
#include <gtest/gtest.h>

#include "molds/thin_ribs.hpp"
#include "primitives.hpp"

namespace fibermold {
namespace {

constexpr double mm = 1e-3;

/// 115 × 30 × 20 mm of 2.5 mm cubes from the origin, the palm at z = 0; six slots `cubes` × 2.5 mm
/// wide and 12.5 mm deep in its back, every 15 mm from x = 20 mm.
SurfaceMesh slotted_finger(int cubes)
{
  return test::voxel_body({0, -15 * mm, 0}, 2.5 * mm, {46, 12, 8}, [cubes](int i, int, int k) {
    const bool slot = i >= 8 && i < 44 && (i - 8) % 6 < cubes && k >= 3;
    return !slot;
  });
}

TEST(ThinRibs, EachNarrowSlotHoldsARibAsThickAsItIsWideAndAsDeep)
{
  // Pull −z (the grooves open toward the palm): the plane at z = 6.65 mm, below the slots' floors
  // (7.5 mm); the back and its slots are the lower half's (along +z).
  const Parting parting{{0, 0, 6.65 * mm}, {0, 0, -1}, 0};
  const std::vector<ThinRib> ribs = thin_ribs(slotted_finger(1), parting, kThinRib / 12);
  ASSERT_EQ(ribs.size(), 6u);
  std::vector<double> xs;
  for (const ThinRib& r : ribs) {
    std::printf("rib: %s half, %.2f mm thick, %.2f mm deep, tip at (%.2f, %.2f, %.2f) mm\n",
                r.upper ? "upper" : "lower", r.thickness / mm, r.depth / mm, r.at.x() / mm, r.at.y() / mm,
                r.at.z() / mm);
    EXPECT_FALSE(r.upper);
    EXPECT_NEAR(r.thickness / mm, 2.5, 0.25);
    EXPECT_NEAR(r.depth / mm, 12.5, 0.01);
    EXPECT_NEAR(r.at.z() / mm, 7.5, 0.01);
    EXPECT_LT(std::abs(r.at.y()), 15 * mm);
    xs.push_back(r.at.x() / mm);
  }
  std::sort(xs.begin(), xs.end());
  for (std::size_t k = 0; k < xs.size(); ++k)
    EXPECT_NEAR(xs[k], 21.25 + 15.0 * static_cast<double>(k), 0.25); // the slot's middle
}

TEST(ThinRibs, SlotsWiderThanAThinRibHoldNone)
{
  const Parting parting{{0, 0, 6.65 * mm}, {0, 0, -1}, 0};
  EXPECT_TRUE(thin_ribs(slotted_finger(2), parting, kThinRib / 12).empty());
  // Parted above the slots' floors, the narrow slots' ribs are shallower: 20 − 12 = 8 mm still
  // stands over 3 × 2.5 mm; at 15 mm, 5 mm does not.
  EXPECT_EQ(thin_ribs(slotted_finger(1), {{0, 0, 12 * mm}, {0, 0, -1}, 0}, kThinRib / 12).size(), 6u);
  EXPECT_TRUE(thin_ribs(slotted_finger(1), {{0, 0, 15 * mm}, {0, 0, -1}, 0}, kThinRib / 12).empty());
}

TEST(ThinRibs, StopsWhenAskedTo)
{
  struct Stopped : Progress {
    void update(double, std::string_view) override {}
    bool interrupted() const override { return true; }
  } stopped;
  EXPECT_THROW(thin_ribs(slotted_finger(1), {{0, 0, 6.65 * mm}, {0, 0, -1}, 0}, kThinRib / 12, &stopped), Interrupted);
}

} // namespace
} // namespace fibermold
