// Thin deep ribs: a gripper-like finger with narrow slots in its back, parted between its palm and
// the slots' floors, has a rib of the half that holds its back standing in each slot, as thick as
// the slot is wide and as deep; with slots twice as wide (thicker than kThinRib) none is thin.
#include <cmath>

#include <Eigen/Geometry>
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

/// slotted_finger(cubes) shortened along x by `squeeze` (its slots 2.5 × cubes × squeeze mm wide) and
/// turned by `degrees` about z, so that its slots run across the height map's grid.
SurfaceMesh turned_finger(int cubes, double squeeze, double degrees)
{
  SurfaceMesh finger = slotted_finger(cubes);
  finger.vertices.col(0) *= squeeze;
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(degrees * M_PI / 180, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  finger.vertices = (finger.vertices * turn.transpose()).eval();
  return finger;
}

TEST(ThinRibs, ASlotsRibIsFoundByItsWidthWhicheverWayTheSlotRuns)
{
  const Parting parting{{0, 0, 6.65 * mm}, {0, 0, -1}, 0};
  for (const double degrees : {0.0, 30.0, 45.0}) {
    // 2.5 mm slots: a thin rib each, as thick as the slot is wide.
    const std::vector<ThinRib> ribs = thin_ribs(turned_finger(1, 1, degrees), parting, kThinRib / 12);
    EXPECT_EQ(ribs.size(), 6u) << degrees << "°";
    for (const ThinRib& r : ribs) {
      std::printf("turned %.0f°: rib %.2f mm thick, %.2f mm deep\n", degrees, r.thickness / mm, r.depth / mm);
      EXPECT_NEAR(r.thickness / mm, 2.5, 0.4) << degrees << "°";
      EXPECT_NEAR(r.depth / mm, 12.5, 0.3) << degrees << "°";
    }
    // 3.75 mm slots hold a rib thicker than kThinRib, which stands firm: none, nor any sliver along
    // their walls (a square closing, √2 wider across a diagonal slot, left 0.4 mm "ribs" there).
    const std::vector<ThinRib> wide = thin_ribs(turned_finger(2, 0.75, degrees), parting, kThinRib / 12);
    EXPECT_TRUE(wide.empty()) << degrees << "°: " << wide.size() << " ribs, the first "
                              << (wide.empty() ? 0 : wide[0].thickness / mm) << " mm thick";
  }
}

/// A 40 × 30 × 20 mm block from the origin with a groove in its top as the molds cut one for a muscle:
/// a slot `width` wide turned `degrees` about z through the block's middle, its walls straight down to
/// z = 10 mm and its bottom half a cylinder of that diameter. The top is a height map every 0.2 mm.
SurfaceMesh grooved_block(double width, double degrees)
{
  const double step = 0.2 * mm, a = degrees * M_PI / 180;
  const int n = 200, m = 150; // cells along x and y
  const auto height = [&](double x, double y) {
    const double d = std::abs(-(x - 20 * mm) * std::sin(a) + (y - 15 * mm) * std::cos(a)), r = width / 2;
    return d < r ? 10 * mm - std::sqrt(r * r - d * d) : 20 * mm;
  };
  SurfaceMesh s;
  s.vertices.resize(2 * (n + 1) * (m + 1), 3);
  const auto at = [&](int i, int j, int top) { return top * (n + 1) * (m + 1) + i * (m + 1) + j; };
  for (int top = 0; top < 2; ++top)
    for (int i = 0; i <= n; ++i)
      for (int j = 0; j <= m; ++j)
        s.vertices.row(at(i, j, top)) << i * step, j * step, top ? height(i * step, j * step) : 0.0;
  std::vector<Eigen::Vector3i> faces;
  const auto quad = [&](int p, int q, int r, int t) { // p q r t counter-clockwise seen from outside
    faces.emplace_back(p, q, r);
    faces.emplace_back(p, r, t);
  };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) {
      quad(at(i, j, 1), at(i + 1, j, 1), at(i + 1, j + 1, 1), at(i, j + 1, 1));
      quad(at(i, j, 0), at(i, j + 1, 0), at(i + 1, j + 1, 0), at(i + 1, j, 0));
    }
  for (int i = 0; i < n; ++i) {
    quad(at(i, 0, 0), at(i + 1, 0, 0), at(i + 1, 0, 1), at(i, 0, 1));
    quad(at(i + 1, m, 0), at(i, m, 0), at(i, m, 1), at(i + 1, m, 1));
  }
  for (int j = 0; j < m; ++j) {
    quad(at(0, j + 1, 0), at(0, j, 0), at(0, j, 1), at(0, j + 1, 1));
    quad(at(n, j, 0), at(n, j + 1, 0), at(n, j + 1, 1), at(n, j, 1));
  }
  s.faces.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t f = 0; f < faces.size(); ++f) s.faces.row(static_cast<Eigen::Index>(f)) = faces[f];
  return s;
}

TEST(ThinRibs, AMusclesGrooveWiderThanAThinRibHoldsNoneAlongItsWalls)
{
  // The twisting bar's grooves (3.6 mm across, round-bottomed, running aslant) were each reported as
  // ribs 0.4 mm thick along one wall: the closing misses the cell along the wall of a valley a cell
  // wider than its disk. The rib in such a groove is as thick as the groove is wide: none is thin.
  const Parting parting{{0, 0, 6.65 * mm}, {0, 0, -1}, 0};
  for (const double degrees : {0.0, 26.0, 45.0}) {
    const std::vector<ThinRib> wide = thin_ribs(grooved_block(3.6 * mm, degrees), parting, kThinRib / 12);
    EXPECT_TRUE(wide.empty()) << degrees << "°: " << wide.size() << " ribs, the first "
                              << (wide.empty() ? 0 : wide[0].thickness / mm) << " mm thick";
    // A 2.5 mm groove's rib is thin, and stands from the top (20 mm) to the groove's bottom (8.75 mm).
    const std::vector<ThinRib> narrow = thin_ribs(grooved_block(2.5 * mm, degrees), parting, kThinRib / 12);
    ASSERT_EQ(narrow.size(), 1u) << degrees << "°";
    std::printf("groove turned %.0f°: rib %.2f mm thick, %.2f mm deep\n", degrees, narrow[0].thickness / mm,
                narrow[0].depth / mm);
    EXPECT_NEAR(narrow[0].thickness / mm, 2.5, 0.4) << degrees << "°";
    EXPECT_NEAR(narrow[0].depth / mm, 11.25, 0.1) << degrees << "°";
  }
}

TEST(ThinRibs, ANarrowFingersSlotHoldsItsRibThoughTheGroundBesideItIsLow)
{
  // A finger 4 mm wide, 40 mm long and 20 mm high (0.5 mm cubes) with one slot 2.5 mm wide and 12.5 mm
  // deep across it at x = 20 mm: the plane around the finger lies lower than the slot's floor within
  // a disk's reach of the rib, which must not make the rib look thick.
  const SurfaceMesh finger = test::voxel_body({0, -2 * mm, 0}, 0.5 * mm, {80, 8, 40},
                                              [](int i, int, int k) { return !(i >= 40 && i < 45 && k >= 15); });
  const std::vector<ThinRib> ribs = thin_ribs(finger, {{0, 0, 6.65 * mm}, {0, 0, -1}, 0}, kThinRib / 12);
  ASSERT_EQ(ribs.size(), 1u);
  EXPECT_NEAR(ribs[0].thickness / mm, 2.5, 0.3);
  EXPECT_NEAR(ribs[0].depth / mm, 12.5, 0.01);
  EXPECT_NEAR(ribs[0].at.x() / mm, 21.25, 0.3);
}

TEST(ThinRibs, ANotchWiderThanAThinRibHoldsNoneInItsCorners)
{
  // The notched finger's notches, 4 mm wide and deep, cut through a 12 × 12 mm finger (0.5 mm cubes):
  // the closing's disk does not reach into a notch's corners, which must not read as thin ribs, the
  // notch square to the map's grid or turned 30° to it.
  for (const double degrees : {0.0, 30.0}) {
    SurfaceMesh finger = test::voxel_body({0, -6 * mm, 0}, 0.5 * mm, {80, 24, 24},
                                          [](int i, int j, int) { return !(i >= 36 && i < 44 && j < 8); });
    const Eigen::Matrix3d turn = Eigen::AngleAxisd(degrees * M_PI / 180, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    finger.vertices = (finger.vertices * turn.transpose()).eval();
    const std::vector<ThinRib> ribs = thin_ribs(finger, {{0, 0, 2 * mm}, {0, 0, 1}, 0}, kThinRib / 12);
    EXPECT_TRUE(ribs.empty()) << degrees << "°: " << ribs.size() << " ribs, the first "
                              << (ribs.empty() ? 0 : ribs[0].thickness / mm) << " mm thick";
  }
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
