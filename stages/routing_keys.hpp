#pragma once
// The design keys that the routing problem of eq. 4 reads (routing_evaluation.hpp's DesignRouting),
// declared by both stages that solve it, optimize and collide: the units, the body's material and
// simulation, what holds it, the muscles and their starting routes, the targets and the tracking
// curves, the optimizer's settings, and the mold terms of the skin distance (skin_distance.hpp).

#include <initializer_list>
#include <string>
#include <vector>

namespace fibermold {

/// The routing problem's keys, then a stage's `own`.
inline std::vector<std::string> routing_design_keys(std::initializer_list<std::string> own)
{
  std::vector<std::string> keys{"design.units",
                                "material",
                                "sim",
                                "fixed",
                                "muscle",
                                "fiber",
                                "tracking_curve",
                                "target",
                                "optimize",
                                "mold.groove_clearance",
                                "mold.min_silicone"};
  keys.insert(keys.end(), own);
  return keys;
}

} // namespace fibermold
