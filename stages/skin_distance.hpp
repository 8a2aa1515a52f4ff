#pragma once
// How far inside the skin a fiber's centre line must stay: one rule, derived here, for check,
// optimize (the skin barrier's d_min), collide (the clearance to the skin it keeps) and molds (the
// room a groove needs), so that a route one stage accepts no later stage refuses
// (docs/optimize.md, "The distance from the skin").

#include <string>

#include "design/design.hpp"

namespace fibermold {

struct SkinDistance {
  /// m: the muscle's radius + the larger of [collide] clearance and the groove's need beyond the
  /// muscle, [mold] groove_clearance + the silicone beside the groove (half the clearance, and at
  /// least [mold] min_silicone, which the molds' thickness check asks).
  double distance = 0;
  /// m: what the groove needs of the fiber's centre line in the molds: the groove's radius
  /// (muscle radius + groove_clearance) + that silicone; never more than `distance`.
  double groove = 0;
  std::string groove_terms; ///< the groove's terms, for a message
  /// m: `distance` − (radius + clearance): how much more than the clearance the skin is kept
  /// away from the muscle for the groove's sake (0 unless groove_clearance + the silicone beside
  /// the groove exceeds the clearance).
  double groove_margin = 0;
  /// The terms, for a message: "[muscle] diameter/2 = 1.5 mm + [collide] clearance = 1 mm".
  std::string terms;
};

SkinDistance skin_distance(const Design& d);

} // namespace fibermold
