#pragma once
// SI inside; millimetres and kilopascals only at the edges (design file, STL, reports).

#include <string>

#include <Eigen/Core>

namespace fibermold::units {

inline constexpr double mm = 1e-3; ///< metres per millimetre
inline constexpr double kPa = 1e3; ///< pascals per kilopascal
inline constexpr double mm3_per_mL = 1e3;
inline constexpr double mm2 = 1e-6;                            ///< square metres per square millimetre
inline constexpr double mm3 = 1e-9;                            ///< cubic metres per cubic millimetre
inline constexpr double mL = 1e-6;                             ///< cubic metres per millilitre
inline constexpr double gram = 1e-3;                           ///< kilograms per gram
inline constexpr double degree = 3.14159265358979323846 / 180; ///< radians per degree

} // namespace fibermold::units

namespace fibermold {

/// A point for a message or a log: "(x, y, z) mm", to a tenth of a millimetre.
std::string format_mm(const Eigen::Vector3d& p);
/// A box's size for a message: "250.0 × 210.0 × 210.0 mm".
std::string format_size_mm(const Eigen::Vector3d& size);

} // namespace fibermold
