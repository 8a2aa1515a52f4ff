// The thinnest-wall check on parts of known thickness: thin walls and tapering wedges are found at
// their thickness; a corner, even a tiny overhanging step such as a level-set mesh leaves, is not a
// wall.
#include <gtest/gtest.h>

#include "molds/mesh_boolean.hpp"
#include "molds/part_checks.hpp"
#include "molds/solids.hpp"
#include "primitives.hpp"

namespace fibermold {
namespace {

constexpr double mm = 1e-3;
const Eigen::Vector3d kPrinter(0.25, 0.21, 0.21);

/// box_solid with the vertices at (x, ·, z) moved to (x', ·, z').
SurfaceMesh moved(SurfaceMesh m, double x, double z, double to_x, double to_z)
{
  for (Eigen::Index i = 0; i < m.num_vertices(); ++i)
    if (std::abs(m.vertices(i, 0) - x) < 1e-9 && std::abs(m.vertices(i, 2) - z) < 1e-9)
      m.vertices(i, 0) = to_x, m.vertices(i, 2) = to_z;
  return m;
}

TEST(PartChecks, ThinPlateIsFoundAtItsThickness)
{
  const PartCheck c = check_part(box_solid({0, 0, 0}, {20 * mm, 20 * mm, 0.6 * mm}), 1 * mm, kPrinter);
  EXPECT_NEAR(c.min_thickness, 0.6 * mm, 1e-6);
  ASSERT_EQ(c.problems.size(), 1u);
  EXPECT_NE(c.problems[0].find("has a wall of 0.60 mm"), std::string::npos) << c.problems[0];
}

TEST(PartChecks, WedgeIsFoundWhereItThinsOut)
{
  // A ramp from 10 mm high at x = 0 down to 0.5 mm at x = 20 mm (a 25° wedge), faces 0.5 mm long: the
  // faces next to the thin end see about 0.5 mm (the wall is measured at face centres).
  SurfaceMesh ramp = test::box({0, 0, 0}, {20 * mm, 20 * mm, 10 * mm}, Eigen::Vector3i(40, 4, 4));
  ramp.vertices.col(2).array() *= 1 - 0.95 * ramp.vertices.col(0).array() / (20 * mm);
  const PartCheck c = check_part(ramp, 1 * mm, kPrinter);
  std::printf("wedge: thinnest %.3f mm\n", c.min_thickness / mm);
  EXPECT_GT(c.min_thickness, 0.5 * mm);
  EXPECT_LT(c.min_thickness, 0.9 * mm);
  EXPECT_FALSE(c.ok());
}

TEST(PartChecks, CornerOfATinyOverhangingStepIsNoWall)
{
  // A 10 mm block with a step 0.03 mm high on half its top, whose riser leans out by 5°: the riser's
  // inward rays leave through the step's top within 0.3 mm, at a right angle to it.
  const SurfaceMesh block = box_solid({0, 0, 0}, {20 * mm, 20 * mm, 10 * mm});
  const SurfaceMesh step = moved(box_solid({0, 0, 9 * mm}, {10 * mm, 20 * mm, 10.03 * mm}), 10 * mm, 10.03 * mm,
                                 10 * mm + 0.03 * mm * std::tan(5 * M_PI / 180), 10.03 * mm);
  const PartCheck c = check_part(mesh_union(block, step), 1 * mm, kPrinter);
  for (const auto& p : c.problems) ADD_FAILURE() << p;
  EXPECT_GT(c.min_thickness, 9 * mm);
}

} // namespace
} // namespace fibermold
