#pragma once
// The clearance barrier between fibers, for optimizing again after collide (the paper's suggestion,
// section V-B): keeps every pair of fibers at least c_min apart,
//   B = Σ_i h_i b((c_i − c_min) / w, 1)  ≈  ∫ b ds
// over the contacts i of fiber_clearance.hpp between two fibers (one per sample segment of a fiber
// and other fiber) with c_i < c_min + w; h_i is that segment's length (mm) on the starting routing,
// so that B does not grow with the sampling; b is the IPC log barrier (barrier.hpp), +∞ once a
// clearance falls to c_min. The closest points are linear in the control points and tangents at
// their segment positions, and ∂c_i/∂p_a = n_i = −∂c_i/∂p_b.

#include <vector>

#include "optimize/fiber_clearance.hpp"
#include "sim/muscle_energy.hpp"

namespace fibermold {

class ClearanceBarrier {
public:
  /// `start`: the routing whose sample spacing gives the h_i.
  ClearanceBarrier(const FiberClearance& measure, const std::vector<Route>& start, double clearance, double band);

  double value(const std::vector<Route>& routes) const;
  /// ∂B/∂(points, tangents) of every fiber (pressure entries 0); zero where B is +∞. With `only` ≥ 0,
  /// that of the terms of the pairs that include fiber `only`: all that changes as it alone moves.
  std::vector<FiberParameterGradient> gradient(const std::vector<Route>& routes, int only = -1) const;

private:
  const FiberClearance& measure_;
  double min_, band_;
  std::vector<std::vector<double>> length_; ///< [fiber][segment], mm
};

} // namespace fibermold
