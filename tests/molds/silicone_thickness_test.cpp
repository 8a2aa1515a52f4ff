// The cast silicone's thickness at the grooves (molds/silicone_thickness.hpp) on a 30 × 20 × 20 mm
// box body with a straight fiber: a groove 0.3 mm from the side skin leaves a 0.3 mm web, and the
// overmold over the laid muscle is the skin's height less the muscle's top.
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "molds/groove.hpp"
#include "molds/silicone_thickness.hpp"
#include "molds/solids.hpp"

namespace fibermold {
namespace {

constexpr double mm = 1e-3;

struct Box {
  SurfaceMesh body = box_solid({0, -10 * mm, -10 * mm}, {30 * mm, 10 * mm, 10 * mm});
  double muscle = 1.5 * mm, radius = 1.8 * mm;

  /// A fiber along x at (y, z), its ends on the end faces (5 mm of it exempt at each).
  SiliconeThickness at(double y, double z, double voxel) const
  {
    const std::vector<Eigen::Vector3d> fiber{{0, y, z}, {15 * mm, y, z}, {30 * mm, y, z}};
    std::vector<Eigen::Vector3d> dense;
    for (int k = 0; k <= 60; ++k) dense.push_back({k * 0.5 * mm, y, z});
    const GrooveBody g = groove_body(body, {fiber}, radius, {0, 0, 1}, voxel);
    return silicone_thickness(g.mesh, body, {dense}, radius, muscle, {0, 0, 1}, voxel, {ExitStretches{5 * mm, 5 * mm}});
  }
};

TEST(SiliconeThickness, AGrooveNearTheSideLeavesAThinWeb)
{
  const Box b;
  // The groove's wall at y = 9.7 mm, the skin at 10: a 0.3 mm web along the whole groove.
  const double voxel = 0.1 * mm;
  const SiliconeThickness thin = b.at(10 * mm - 0.3 * mm - b.radius, 0, voxel);
  std::printf("web %.3f mm at (%.1f, %.1f, %.1f) mm; over the muscle %.3f mm\n", thin.groove_web / mm,
              thin.groove_web_at.x() / mm, thin.groove_web_at.y() / mm, thin.groove_web_at.z() / mm,
              thin.overmold / mm);
  EXPECT_NEAR(thin.groove_web, 0.3 * mm, 1.5 * voxel);
  EXPECT_GT(thin.groove_web_at.y(), 9 * mm); // on the side toward the skin
  EXPECT_GT(thin.groove_web_at.x(), 5 * mm); // not at the ends, which are exempt
  EXPECT_LT(thin.groove_web_at.x(), 25 * mm);

  // On the axis the walls are 8.2 mm from the sides and the floor 8.2 mm above the bottom: no
  // silicone under 2 mm thick to report.
  const SiliconeThickness middle = b.at(0, 0, 0.25 * mm);
  EXPECT_FALSE(std::isfinite(middle.groove_web));

  // 1.2 mm from the bottom instead: the floor's web.
  const SiliconeThickness low = b.at(0, -10 * mm + 1.2 * mm + b.radius, voxel);
  EXPECT_NEAR(low.groove_web, 1.2 * mm, 1.5 * voxel);
  EXPECT_LT(low.groove_web_at.z(), -8 * mm);
}

TEST(SiliconeThickness, OvermoldIsTheSkinAboveTheLaidMusclesTop)
{
  const Box b;
  // Fiber at z = 6 mm: the laid muscle's axis 0.3 mm lower, its top at 7.2 mm, the skin at 10.
  const SiliconeThickness t = b.at(0, 6 * mm, 0.25 * mm);
  EXPECT_NEAR(t.overmold, 10 * mm - (6 * mm + 2 * b.muscle - b.radius), 1e-9);
  EXPECT_NEAR(t.overmold_at.z(), 10 * mm, 1e-9);
}

} // namespace
} // namespace fibermold
