#include "stages/skin_distance.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "core/units.hpp"

namespace fibermold {

SkinDistance skin_distance(const Design& d)
{
  const double radius = d.muscle.model.radius(), clearance = d.collide.clearance, groove = d.mold.groove_clearance;
  // Beside the groove: half the clearance, and no less silicone than the molds' thickness check asks.
  const double web = std::max(clearance / 2, d.mold.min_silicone);
  SkinDistance s;
  s.groove = radius + groove + web;
  s.distance = radius + std::max(clearance, groove + web);
  s.groove_margin = s.distance - (radius + clearance);
  s.groove_terms = fmt::format("[muscle] diameter/2 = {:.3g} mm + [mold] groove_clearance = {:.3g} mm + {} = {:.3g} mm",
                               radius / units::mm, groove / units::mm,
                               clearance / 2 >= d.mold.min_silicone ? "[collide] clearance/2" : "[mold] min_silicone",
                               web / units::mm);
  s.terms = s.groove_margin > 0 ? s.groove_terms + ", what the groove needs"
                                : fmt::format("[muscle] diameter/2 = {:.3g} mm + [collide] clearance = {:.3g} mm",
                                              radius / units::mm, clearance / units::mm);
  return s;
}

} // namespace fibermold
