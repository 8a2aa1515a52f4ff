#pragma once
// The clearance barrier between fibers, for optimizing again after collide (the paper's suggestion,
// section V-B): keeps every pair of fibers at least c_min apart,
//   B = Σ_i b((c_i − c_min) / w, 1)
// over the contacts i of fiber_clearance.hpp between two fibers (one per sample segment of a fiber
// and other fiber) with c_i < c_min + w; b is the IPC log barrier (barrier.hpp), +∞ once a
// clearance falls to c_min. The closest points are linear in the control points and tangents at
// their segment positions, and ∂c_i/∂p_a = n_i = −∂c_i/∂p_b.

#include <vector>

#include "optimize/fiber_clearance.hpp"
#include "sim/muscle_energy.hpp"

namespace fibermold {

class ClearanceBarrier {
public:
  ClearanceBarrier(const FiberClearance& measure, double clearance, double band)
      : measure_(measure), min_(clearance), band_(band)
  {
  }

  double value(const std::vector<Route>& routes) const;
  /// ∂B/∂(points, tangents) of every fiber (pressure entries 0); zero where B is +∞.
  std::vector<FiberParameterGradient> gradient(const std::vector<Route>& routes) const;

private:
  const FiberClearance& measure_;
  double min_, band_;
};

} // namespace fibermold
