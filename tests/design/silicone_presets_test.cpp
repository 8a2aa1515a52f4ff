// The silicone presets: each one's Neo-Hookean shear modulus, as fibermold simulates it (compressible,
// lateral faces free), reproduces its material's public uniaxial tensile data over the fit window, and
// is that data's least-squares fit; the design file takes a preset's figures as the keys' defaults.
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include <gtest/gtest.h>

#include "design/design_file.hpp"
#include "molds/silicone_presets.hpp"
#include "sim/neo_hookean.hpp"
#include "test_support.hpp"

namespace fibermold {
namespace {

/// The nominal stress P₁₁ of a uniaxial stretch `a` along x with the lateral faces free: the lateral
/// stretch b found where P₂₂ = 0 (bisection), from fibermold's own Neo-Hookean stress.
double uniaxial_stress(double a, const LameParameters& lame)
{
  const auto stress = [&](double b) { return neo_hookean_stress(Eigen::Vector3d(a, b, b).asDiagonal(), lame); };
  double lo = 0.1, hi = 1.5;
  for (int i = 0; i < 100; ++i) {
    const double b = 0.5 * (lo + hi);
    (stress(b)(1, 1) > 0 ? hi : lo) = b;
  }
  return stress(0.5 * (lo + hi))(0, 0);
}

/// preset → (engineering strain, engineering stress in Pa), from the data file.
std::map<std::string, std::vector<std::pair<double, double>>> tensile_data()
{
  std::map<std::string, std::vector<std::pair<double, double>>> data;
  std::istringstream lines(test::read_text(std::filesystem::path(FIBERMOLD_SOURCE_DIR) / "tests" / "design" / "data" /
                                           "silicone_tensile.csv"));
  for (std::string line; std::getline(lines, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream cells(line);
    std::string preset, strain, stress;
    std::getline(cells, preset, ',');
    std::getline(cells, strain, ',');
    std::getline(cells, stress, ',');
    data[preset].emplace_back(std::stod(strain), std::stod(stress));
  }
  return data;
}

TEST(SiliconePresets, EachReproducesItsTensileDataOverTheFitWindow)
{
  const auto data = tensile_data();
  ASSERT_EQ(data.size(), silicone_presets().size());
  for (const SiliconePreset& preset : silicone_presets()) {
    SCOPED_TRACE(preset.key);
    ASSERT_TRUE(data.contains(preset.key));
    const auto& points = data.at(preset.key);
    ASSERT_GE(points.size(), 15u);
    EXPECT_LE(points.back().first, kPresetFitStrain);
    EXPECT_GE(points.back().first, 0.9 * kPresetFitStrain);
    const LameParameters lame = LameParameters::from_young_poisson(preset.youngs_modulus(), kPresetPoissonRatio);
    // The stress is linear in μ at a fixed Poisson ratio: the least-squares μ in closed form.
    double gp = 0, gg = 0, squared = 0, largest = 0, worst = 0;
    for (const auto& [strain, stress] : points) {
      const double model = uniaxial_stress(1 + strain, lame), per_mu = model / lame.mu;
      gp += per_mu * stress, gg += per_mu * per_mu;
      squared += (model - stress) * (model - stress);
      largest = std::max(largest, stress);
      // Below 20 % the crosshead's slack shows (the first points are near zero, one negative).
      if (strain >= 0.2) worst = std::max(worst, std::abs(model - stress) / stress);
    }
    const double rms = std::sqrt(squared / static_cast<double>(points.size()));
    std::printf("%-15s mu %6.2f kPa (least squares %6.2f kPa), E %6.1f kPa: RMS %5.2f kPa = %4.1f %% of %6.1f kPa; "
                "worst from 20 %% strain %4.1f %%\n",
                preset.key.c_str(), lame.mu / 1e3, gp / gg / 1e3, preset.youngs_modulus() / 1e3, rms / 1e3,
                100 * rms / largest, largest / 1e3, 100 * worst);
    EXPECT_NEAR(lame.mu, gp / gg, 0.005 * lame.mu); // the preset is the fit
    EXPECT_LT(rms, 0.08 * largest);                 // the stated error: docs/design-file.md
    EXPECT_LT(worst, 0.15);
  }
}

TEST(SiliconePresets, APresetSetsTheMaterialsDefaultsAndTheKeysOverrideIt)
{
  test::TempDir dir;
  test::write_bar(dir.path());
  const auto read = [&](const std::string& material) {
    test::write_text(dir / "design.toml", "[design]\nsurface = \"bar.stl\"\n[material]\n" + material);
    return load_design(dir / "design.toml").material;
  };
  const SiliconePreset& dragon = *find_silicone_preset("dragon-skin-10");
  const MaterialOptions preset = read("preset = \"dragon-skin-10\"\n");
  EXPECT_EQ(preset.preset, "dragon-skin-10");
  EXPECT_DOUBLE_EQ(preset.youngs_modulus, 2 * dragon.shear_modulus * (1 + 0.47));
  EXPECT_DOUBLE_EQ(preset.poisson_ratio, 0.47);
  EXPECT_DOUBLE_EQ(preset.density, 1070);
  const MaterialOptions overridden = read("preset = \"dragon-skin-10\"\nyoungs_modulus = 150e3\n");
  EXPECT_DOUBLE_EQ(overridden.youngs_modulus, 150e3);
  EXPECT_DOUBLE_EQ(overridden.density, 1070);
  const MaterialOptions none = read("");
  EXPECT_EQ(none.preset, "");
  EXPECT_DOUBLE_EQ(none.youngs_modulus, 86.4e3); // the paper's EcoFlex 00-30
  try {
    read("preset = \"dragonskin-10\"\n");
    FAIL() << "an unknown preset was taken";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("design.toml:4:10: [material].preset: unknown value \"dragonskin-10\""),
              std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("did you mean \"dragon-skin-10\"?"), std::string::npos) << e.what();
  }
}

} // namespace
} // namespace fibermold
