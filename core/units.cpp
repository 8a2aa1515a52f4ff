#include "core/units.hpp"

#include <cmath>

#include <fmt/format.h>

namespace fibermold {

std::string format_mm(const Eigen::Vector3d& p)
{
  // Rounded to the tenth first: −0.04 mm would print as "-0.0"; + 0.0 turns −0 into 0.
  const auto tenth = [](double v) { return std::round(v / units::mm * 10) / 10 + 0.0; };
  return fmt::format("({:.1f}, {:.1f}, {:.1f}) mm", tenth(p.x()), tenth(p.y()), tenth(p.z()));
}

std::string format_size_mm(const Eigen::Vector3d& size)
{
  return fmt::format("{:.1f} × {:.1f} × {:.1f} mm", size.x() / units::mm, size.y() / units::mm, size.z() / units::mm);
}

} // namespace fibermold
