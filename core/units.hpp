#pragma once
// SI inside; millimetres and kilopascals only at the edges (design file, STL, reports).

namespace fibermold::units {

inline constexpr double mm = 1e-3;   ///< metres per millimetre
inline constexpr double kPa = 1e3;   ///< pascals per kilopascal
inline constexpr double mm3_per_mL = 1e3;

} // namespace fibermold::units
