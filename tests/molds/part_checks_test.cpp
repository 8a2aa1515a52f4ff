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

// A part fits the printer in the axis-aligned orientation of least build height, or is refused naming both sizes.
TEST(PartChecks, APartFitsThePrinterLowestOrNotAtAll)
{
  const SurfaceMesh bar = box_solid({0, 0, 0}, {80 * mm, 30 * mm, 10 * mm});
  const PartCheck small = check_part(bar, 1 * mm, Eigen::Vector3d(0.05, 0.05, 0.05));
  ASSERT_EQ(small.problems.size(), 1u);
  EXPECT_EQ(small.problems[0],
            "is 80.0 × 30.0 × 10.0 mm and does not fit the printer's 50.0 × 50.0 × 50.0 mm in any of "
            "the 6 orientations");
  EXPECT_FALSE(small.fits);
  // Stood on its end it would fit a 40 × 40 × 90 mm printer too, but lying down it builds 10 mm high.
  const PartCheck fits = check_part(bar, 1 * mm, Eigen::Vector3d(0.09, 0.04, 0.09));
  EXPECT_TRUE(fits.ok()) << fits.problems.front();
  EXPECT_EQ(fits.orientation, Eigen::Vector3i(0, 1, 2));
  EXPECT_EQ(printer_orientation(Eigen::Vector3d(0.08, 0.03, 0.01), Eigen::Vector3d(0.04, 0.04, 0.09)),
            Eigen::Vector3i(1, 2, 0)); // only on its end
  EXPECT_FALSE(printer_orientation(Eigen::Vector3d(0.08, 0.03, 0.01), Eigen::Vector3d(0.07, 0.07, 0.07)));
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
