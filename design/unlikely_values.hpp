#pragma once
// Values inside their physical ranges (design_file.cpp refuses the rest) that a soft robot seldom
// has and that a number given in another unit gives: a pressure in MPa where kPa are read, an angle
// in radians where degrees are, a length in metres where millimetres are. Each is a warning, not an
// error (a 0.5° turn may be meant), naming the key, its line, the value and what it would be in the
// unit it was likely written in. `check` prints them; `make` logs them before the stages run.

#include <vector>

#include "core/input_error.hpp"
#include "design/design.hpp"

namespace fibermold {

/// A pneumatic muscle works at tens to hundreds of kPa: under this (kPa) max_pressure reads as MPa.
inline constexpr double kLeastLikelyPressureKPa = 10;
/// Casting silicones start near 22 kPa (Ecoflex 00-10, silicone_presets.cpp): under this (Pa) youngs_modulus
/// reads as kPa (under 100 Pa the range refuses it).
inline constexpr double kLeastLikelyModulusPa = 1e3;
/// Silicones weigh about 1,000–1,500 kg/m³: under this (kg/m³) density reads as g/cm³.
inline constexpr double kLeastLikelyDensity = 100;
/// A pose's turn of less than this (degrees), not 0, reads as radians when it would be a turn of at
/// most 180° in radians.
inline constexpr double kLeastLikelyTurnDeg = 3.2;
/// A route or a tracking curve spanning less than this (mm) reads as metres.
inline constexpr double kLeastLikelySpanMm = 1;
/// A pose's translation shorter than this (mm), not 0, reads as metres.
inline constexpr double kLeastLikelyTranslationMm = 0.1;

/// The design's values that read as given in another unit, one warning each, at the key's line.
std::vector<Diagnostic> unlikely_values(const Design& d);

} // namespace fibermold
