#include "stages/routing_evaluation.hpp"

#include <gtest/gtest.h>

#include "core/units.hpp"

namespace fibermold {
namespace {

// Each route's smallest bend for the reports: a quarter circle of 20 mm gives about 20 mm, where
// and how far along; a straight route says so rather than leaving its entry empty.
TEST(BendsJson, GivesEachRoutesSmallestBendAndSaysStraight)
{
  const double r = 20 * units::mm, k = 1.657 * r; // a cubic Hermite quarter circle's tangent length
  const std::vector<Route> routes{{"arc",
                                   {Eigen::Vector3d::Zero(), Eigen::Vector3d(r, r, 0)},
                                   {Eigen::Vector3d(k, 0, 0), Eigen::Vector3d(0, k, 0)}},
                                  {"line",
                                   {Eigen::Vector3d::Zero(), Eigen::Vector3d(50 * units::mm, 0, 0)},
                                   {Eigen::Vector3d(50 * units::mm, 0, 0), Eigen::Vector3d(50 * units::mm, 0, 0)}}};
  const nlohmann::ordered_json j = bends_json(routes);
  EXPECT_NEAR(j["arc"]["min_bend_radius_mm"].get<double>(), 20, 1.5);
  EXPECT_GE(j["arc"]["along_mm"].get<double>(), 0);
  EXPECT_LE(j["arc"]["along_mm"].get<double>(), 31.5); // the quarter circle's length, 31.4 mm
  EXPECT_EQ(j["arc"]["at_mm"].size(), 3u);
  EXPECT_FALSE(j["arc"].contains("straight"));
  EXPECT_EQ(j["line"], nlohmann::ordered_json({{"straight", true}}));
}

} // namespace
} // namespace fibermold
