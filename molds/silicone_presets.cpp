#include "molds/silicone_presets.hpp"

#include <algorithm>

namespace fibermold {

namespace {

constexpr double kMinute = 60, kHour = 3600;

} // namespace

double SiliconePreset::youngs_modulus() const { return 2 * shear_modulus * (1 + kPresetPoissonRatio); }

// Shear moduli: least squares of fibermold's Neo-Hookean uniaxial stress (lateral faces free) to the
// Soft Robotics Materials Database's tensile tests up to kPresetFitStrain (tests/design/data/
// silicone_tensile.csv). Handling: Smooth-On's Ecoflex and Dragon Skin series technical bulletins.
const std::vector<SiliconePreset>& silicone_presets()
{
  static const std::vector<SiliconePreset> presets = {
      {"ecoflex-00-10", "Smooth-On Ecoflex 00-10", "Shore 00-10", 7.48e3, 1040, 1, 1, 30 * kMinute, 4 * kHour, false},
      {"ecoflex-00-30", "Smooth-On Ecoflex 00-30", "Shore 00-30", 15.35e3, 1070, 1, 1, 45 * kMinute, 4 * kHour, false},
      {"ecoflex-00-50", "Smooth-On Ecoflex 00-50", "Shore 00-50", 21.10e3, 1070, 1, 1, 18 * kMinute, 3 * kHour, false},
      {"dragon-skin-10", "Smooth-On Dragon Skin 10 Medium", "Shore 10A", 46.91e3, 1070, 1, 1, 20 * kMinute, 5 * kHour,
       true},
      {"dragon-skin-20", "Smooth-On Dragon Skin 20", "Shore 20A", 131.3e3, 1080, 1, 1, 25 * kMinute, 4 * kHour, true},
      {"dragon-skin-30", "Smooth-On Dragon Skin 30", "Shore 30A", 193.7e3, 1080, 1, 1, 45 * kMinute, 16 * kHour, true},
  };
  return presets;
}

const SiliconePreset* find_silicone_preset(const std::string& key)
{
  const auto& all = silicone_presets();
  const auto it = std::find_if(all.begin(), all.end(), [&](const SiliconePreset& p) { return p.key == key; });
  return it == all.end() ? nullptr : &*it;
}

} // namespace fibermold
