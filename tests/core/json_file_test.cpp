#include "core/json_file.hpp"

#include <cmath>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "test_support.hpp"

namespace fibermold {
namespace {

using ::testing::HasSubstr;

TEST(JsonFile, NaNInfinityAndNullAreFoundByTheirPlace)
{
  nlohmann::ordered_json j{{"shots", {{"shot1", {{"silicone_mass_g", 12.5}, {"volume_mL", 3.0}}}}},
                           {"list", {1.0, 2.0}}};
  EXPECT_FALSE(first_non_finite(j).has_value());
  j["shots"]["shot1"]["silicone_mass_g"] = std::nan("");
  EXPECT_EQ(first_non_finite(j).value_or(""), "/shots/shot1/silicone_mass_g");
  j["shots"]["shot1"]["silicone_mass_g"] = 1.0;
  j["list"][1] = HUGE_VAL;
  EXPECT_EQ(first_non_finite(j).value_or(""), "/list/1");
  j["list"][1] = nullptr;
  EXPECT_EQ(first_non_finite(j).value_or(""), "/list/1");
}

TEST(JsonFile, ANonFiniteNumberIsNotWritten)
{
  test::TempDir dir;
  const auto path = dir / "report.json";
  nlohmann::json j{{"fill", {{"trapped_air_mm3", 0.5}}}};
  write_json_atomic(path, j);
  EXPECT_EQ(test::read_text(path), j.dump(2) + "\n");
  j["fill"]["trapped_air_mm3"] = -HUGE_VAL;
  try {
    write_json_atomic(path, j);
    ADD_FAILURE() << "wrote a non-finite number";
  } catch (const std::runtime_error& e) {
    EXPECT_THAT(e.what(), HasSubstr("report.json: /fill/trapped_air_mm3 is not a finite number"));
  }
  const nlohmann::json old{{"fill", {{"trapped_air_mm3", 0.5}}}};
  EXPECT_EQ(test::read_text(path), old.dump(2) + "\n") << "the old file stays";
}

TEST(JsonFile, AnOptionalFileIsReadWhenItIsThereAndParses)
{
  test::TempDir dir;
  EXPECT_FALSE(read_json_if_any<nlohmann::json>(dir / "missing.json"));
  test::write_text(dir / "cut.json", "{\"a\": [1, 2");
  EXPECT_FALSE(read_json_if_any<nlohmann::json>(dir / "cut.json"));
  test::write_text(dir / "report.json", "{\"rounds\": 2}");
  const auto j = read_json_if_any<nlohmann::ordered_json>(dir / "report.json");
  ASSERT_TRUE(j);
  EXPECT_EQ((*j)["rounds"].get<int>(), 2);
}

} // namespace
} // namespace fibermold
