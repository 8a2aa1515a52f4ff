#pragma once
// What every mold the e2e tests make must show of its fill (manifest.json's shots.*.fill): each
// shot's sprues and vents open on what it fills, all of it reached but crevices thinner than the
// simulation's voxel (under 3 % of it), and its trapped air within the tolerance; shot 2 fed from
// above, over cured silicone.
#include <cstdio>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace fibermold::test {

inline void expect_fills(const nlohmann::json& manifest)
{
  for (const char* shot : {"shot1", "shot2"}) {
    const nlohmann::json& f = manifest["shots"][shot]["fill"];
    const double volume = f["fill_volume_mL"].get<double>() * 1e3; // mm³
    const double crevices = f["crevices_unfilled_mm3"].get<double>(), reached = f["reachable_percent"].get<double>();
    std::printf("%s fill: %.1f mm³, %.3f %% reached (crevices %.2f mm³ unfilled, %.2f mm³ of air), %.3f mm³ trapped, "
                "%zu sprue(s), %zu vent(s)\n",
                shot, volume, reached, crevices, f["crevices_air_mm3"].get<double>(),
                f["trapped_air_mm3"].get<double>(), f["sprues"].size(), f["vents"].size());
    EXPECT_GT(volume, 0) << shot;
    EXPECT_NEAR(reached, 100 * (1 - crevices / volume), 1e-3) << shot;
    EXPECT_LT(crevices, 0.03 * volume) << shot; // the crescent under a laid muscle, thinner than a voxel
    EXPECT_LE(f["trapped_air_mm3"].get<double>(), f["trapped_air_tolerance_mm3"].get<double>()) << shot;
    EXPECT_LE(f["trapped_air_tolerance_mm3"].get<double>(), 1.0) << shot;
    ASSERT_GE(f["sprues"].size(), 1u) << shot;
    ASSERT_GE(f["vents"].size(), 1u) << shot;
    for (const auto& s : f["sprues"]) {
      EXPECT_TRUE(s["opens_on_fill_region"].get<bool>()) << shot;
      EXPECT_EQ(s["from"], std::string(shot) == "shot1" ? "below" : "above") << shot;
    }
    for (const auto& v : f["vents"]) EXPECT_TRUE(v["opens_on_fill_region"].get<bool>()) << shot;
  }
}

} // namespace fibermold::test
