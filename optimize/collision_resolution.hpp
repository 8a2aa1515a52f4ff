#pragma once
// Resolution of fiber collisions (the collide stage; the paper moved crossing fibers apart by hand,
// sections V-B and VIII-F). The smallest smooth change of the routes that gives every contact of
// fiber_clearance.hpp its clearance c_min:
//   min_y  ½ Σ_f ∫ ( |Δp_f(s)|² + ℓ⁴ |∂²Δp_f/∂s²|² ) ds   s.t.  c_i(y) ≥ c_min for every contact i,
// with y the interior control points and all tangents (end points fixed), Δp_f the move of fiber
// f's centre line, s its arc length and ℓ the smoothness length: the bending term spreads a move
// along the fiber instead of kinking it. Integrals are sums over the clearance samples.
//
// Sequential linearization: the contacts are measured, each linearized as c_i + n_iᵀ(Δp_a − Δp_b),
// and the quadratic problem solved exactly by an augmented Lagrangian whose inner problem is
// minimized by Newton on its active set (through the contacts: W is block diagonal per fiber);
// then measured again, until every clearance holds and the routes stop moving. Of the contacts
// measured each round only the local minima of clearance along each fiber pair enter (their
// neighbours are near copies of one constraint); a contact once entered stays, measured again
// every round. A routing that is already clear is returned unchanged, bit for bit.

#include <stdexcept>
#include <string>
#include <vector>

#include "optimize/fiber_clearance.hpp"

namespace fibermold {

struct ResolutionSettings {
  double clearance = 1e-3;   ///< c_min, m: what must hold
  double room = 0;           ///< m: where fibers move, they are moved to c_min + room
  double smoothness = 10e-3; ///< ℓ, m
  int max_iterations = 30;   ///< measure–solve rounds
  double tolerance = 1e-6;   ///< m: a clearance this much short of c_min still holds
};

struct CollisionResolution {
  std::vector<Route> routes;
  bool changed = false;
  int iterations = 0;
  double before = 0, after = 0; ///< the smallest clearance, m (+∞: nothing within reach)
  /// At the start: the worst contact of each fiber pair (or fiber and skin) short of c_min.
  std::vector<Contact> collided;
};

/// Clearance that cannot be had: two fixed end points too close, or a passage narrower than the
/// muscles need. The message names the fibers and the place.
class CollisionError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

/// Throws CollisionError when some clearance cannot be restored.
CollisionResolution resolve_collisions(const FiberClearance& measure, const std::vector<Route>& routes,
                                       const ResolutionSettings& settings);

/// The worst contact of each fiber pair (or fiber and skin) among `contacts`.
std::vector<Contact> worst_per_pair(const std::vector<Contact>& contacts);

} // namespace fibermold
