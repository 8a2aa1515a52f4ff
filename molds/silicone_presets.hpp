#pragma once
// Casting silicones by name (`[material] preset`): the Neo-Hookean stiffness fitted to public
// uniaxial tensile data over the strains fibermold's robots see, the density, and the handling
// figures of the manufacturer's technical bulletin that the casting sheet (README.txt) gives.
// Sources and the fit: docs/design-file.md#material-presets.

#include <string>
#include <vector>

namespace fibermold {

struct SiliconePreset {
  std::string key;        ///< "ecoflex-00-30", as `[material] preset` names it
  std::string name;       ///< "Smooth-On Ecoflex 00-30"
  std::string hardness;   ///< "Shore 00-30"
  double shear_modulus;   ///< Pa: μ of the Neo-Hookean at kPresetPoissonRatio, fitted over kPresetFitStrain
  double density;         ///< kg/m³
  double mix_a, mix_b;    ///< parts A : B by weight
  double pot_life;        ///< s, at 23 °C
  double demold_time;     ///< s, the cure time at 23 °C
  bool degas_recommended; ///< the bulletin recommends vacuum degassing

  /// Young's modulus at kPresetPoissonRatio, Pa.
  double youngs_modulus() const;
};

/// The Poisson ratio of every preset: the paper's, nearly incompressible.
inline constexpr double kPresetPoissonRatio = 0.47;
/// The engineering strains over which the stiffness was fitted: the largest principal strain of 99 % of
/// the examples' tetrahedra is below it (docs/design-file.md#material-presets).
inline constexpr double kPresetFitStrain = 0.5;
/// The silicone of the default [material] (the paper's EcoFlex 00-30): whose handling README.txt gives
/// when no preset is named.
inline constexpr const char* kDefaultSilicone = "ecoflex-00-30";

const std::vector<SiliconePreset>& silicone_presets();
/// The preset named `key`; nullptr when there is none.
const SiliconePreset* find_silicone_preset(const std::string& key);

} // namespace fibermold
