#pragma once
// The skin barrier of section V-B: keeps a fiber's samples away from the outside surface of the
// undeformed body,
//   B = Σ_k b(d_k / d̂, 1),   d̂ = muscle radius + clearance,
// with b the IPC log barrier (barrier.hpp), d_k the distance of sample p_k to the skin (AABB
// tree), +∞ once a sample leaves the body. Samples sit at fixed spline parameters, so p_k is
// linear in the control points and tangents. Samples near an end point that lies within d̂ of
// the skin are left out: the fiber leaves the body there by design.

#include <vector>

#include "mesh/surface_distance.hpp"
#include "sim/hermite_spline.hpp"
#include "sim/muscle_energy.hpp"

namespace fibermold {

class SkinBarrier {
public:
  /// `samples` parameters spread by arc length over `initial`, which fixes the excluded ends.
  SkinBarrier(const SurfaceDistance& skin, double dhat, const HermiteSpline& initial, int samples);

  double value(const HermiteSpline& spline) const;
  /// ∂B/∂(points, tangents); the pressure entry is 0. Zero where B is +∞.
  FiberParameterGradient gradient(const HermiteSpline& spline) const;
  /// The smallest distance of a sample to the skin (m), negative when outside.
  double min_distance(const HermiteSpline& spline) const;

private:
  const SurfaceDistance& skin_;
  double dhat_;
  std::vector<double> t_;
};

} // namespace fibermold
