#include "core/units.hpp"

#include <gtest/gtest.h>

namespace fibermold {
namespace {

TEST(Units, APointPrintsInMillimetresToATenthWithoutANegativeZero)
{
  using units::mm;
  EXPECT_EQ(format_mm(Eigen::Vector3d(14.001 * mm, -0.009 * mm, -8.0 * mm)), "(14.0, 0.0, -8.0) mm");
  EXPECT_EQ(format_mm(Eigen::Vector3d(-0.04 * mm, 0.07 * mm, -0.06 * mm)), "(0.0, 0.1, -0.1) mm");
  EXPECT_EQ(format_mm(Eigen::Vector3d(-0.0, 1234.56 * mm, 0.26 * mm)), "(0.0, 1234.6, 0.3) mm");
}

} // namespace
} // namespace fibermold
