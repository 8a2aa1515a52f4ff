#include "design/unlikely_values.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "design/design_file.hpp"
#include "test_support.hpp"

namespace fibermold {
namespace {

using ::testing::HasSubstr;
using ::testing::IsEmpty;

/// A design with one fiber, tracking curve and pose target, in the units the file reads, and `extra`.
Design design(const test::TempDir& dir, const std::string& extra)
{
  test::write_text(dir.path() / "body.stl", "solid x\nendsolid x\n");
  return parse_design(R"([design]
surface = "body.stl"
[[fiber]]
name = "m1"
points = [[6, 0, 12], [20, 0, 8.5], [43, 0, 8.5]]
[[tracking_curve]]
name = "arm"
points = [[14, 0, 6], [48, 0, 6]]
[[target]]
name = "grasp"
kind = "pose"
pose = [{ box = { min = [45, -6, -1], max = [51, 6, 13] }, axis = [0, -1, 0], angle_deg = 40 }]
)" + extra,
                      dir.path() / "design.toml");
}

// A new user's numbers in the units they knew, each read as the file's unit: a warning each, at the
// key's line, with what the number would be in the unit it was likely written in.
TEST(UnlikelyValues, NumbersWrittenInAnotherUnitAreNamedWithTheirLikelyMeaning)
{
  test::TempDir dir;
  EXPECT_THAT(unlikely_values(design(dir, "[muscle]\nmax_pressure = 425\n")), IsEmpty());

  const auto mpa = unlikely_values(design(dir, "[muscle]\nmax_pressure = 0.425\n"));
  ASSERT_EQ(mpa.size(), 1u);
  EXPECT_EQ(mpa[0].key, "[muscle].max_pressure");
  EXPECT_EQ(mpa[0].line, 14);
  EXPECT_THAT(mpa[0].message, HasSubstr("0.425 kPa is less than a pneumatic muscle works at"));
  EXPECT_THAT(mpa[0].message, HasSubstr("if this is MPa, write 425"));

  const auto material = unlikely_values(design(dir, "[material]\nyoungs_modulus = 120\ndensity = 1.07\n"));
  ASSERT_EQ(material.size(), 2u);
  EXPECT_THAT(material[0].message, HasSubstr("if this is kPa, write 120000"));
  EXPECT_THAT(material[1].message, HasSubstr("if this is g/cm³, write 1070"));

  // Metres where mm are read: a route and a tracking curve of a few hundredths of a mm.
  const auto metres = unlikely_values(parse_design(R"([design]
surface = "body.stl"
[[fiber]]
name = "m1"
points = [[0.006, 0, 0.012], [0.043, 0, 0.0085]]
[[tracking_curve]]
name = "arm"
points = [[0.014, 0, 0.006], [0.048, 0, 0.006]]
)",
                                                   dir.path() / "design.toml"));
  ASSERT_EQ(metres.size(), 2u);
  EXPECT_EQ(metres[0].key, "[fiber.m1].points");
  EXPECT_THAT(metres[0].message, HasSubstr("the route's points span 0.0372 mm"));
  EXPECT_THAT(metres[0].message, HasSubstr("if these are metres, they span 37.2 mm"));
  EXPECT_THAT(metres[1].message, HasSubstr("the tracking curve's points span 0.034 mm"));
}

TEST(UnlikelyValues, APoseInRadiansOrMetresIsNamed)
{
  test::TempDir dir;
  const auto pose = [&](const std::string& fields) {
    test::write_text(dir.path() / "body.stl", "solid x\nendsolid x\n");
    return unlikely_values(parse_design(
        "[design]\nsurface = \"body.stl\"\n[[target]]\nname = \"grasp\"\nkind = \"pose\"\npose = [{ box = { min = "
        "[45, -6, -1], max = [51, 6, 13] }, " +
            fields + " }]\n",
        dir.path() / "design.toml"));
  };
  EXPECT_THAT(pose("axis = [0, -1, 0], angle_deg = 40"), IsEmpty());
  const auto radians = pose("axis = [0, -1, 0], angle_deg = 0.698");
  ASSERT_EQ(radians.size(), 1u);
  EXPECT_THAT(radians[0].key, HasSubstr("[target.grasp].pose[1]"));
  EXPECT_THAT(radians[0].message, HasSubstr("a turn of 0.698° is smaller than"));
  EXPECT_THAT(radians[0].message, HasSubstr("if this is radians, write 40.0"));
  const auto metres = pose("translation = [-0.0028, 0, 0.011]");
  ASSERT_EQ(metres.size(), 1u);
  EXPECT_THAT(metres[0].message, HasSubstr("a translation of 0.0114 mm"));
  EXPECT_THAT(metres[0].message, HasSubstr("if this is metres, it is 11.4 mm"));
  EXPECT_THAT(pose("translation = [-2.8, 0, 11]"), IsEmpty());
}

} // namespace
} // namespace fibermold
