#include "core/units.hpp"

#include <fmt/format.h>

namespace fibermold {

std::string format_mm(const Eigen::Vector3d& p)
{
  return fmt::format("({:.1f}, {:.1f}, {:.1f}) mm", p.x() / units::mm, p.y() / units::mm, p.z() / units::mm);
}

} // namespace fibermold
