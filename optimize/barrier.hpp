#pragma once
// The log barrier of IPC (Li et al. 2020), used for the bound constraints of eq. 4 (pressures in
// [0, p_max]) and, later, for the clearance of fibers to the skin (section V-B):
//   b(d) = −(d − d̂)² ln(d / d̂)  for 0 < d < d̂,   0 for d ≥ d̂,   +∞ for d ≤ 0.
// C² at d̂; b → ∞ as d → 0.

namespace fibermold {

double barrier(double d, double dhat);
/// b'(d) = (d̂ − d)(2 ln(d/d̂) − d̂/d + 1)
double barrier_gradient(double d, double dhat);
/// b''(d) = −2 ln(d/d̂) − (d − d̂)(3d + d̂)/d²
double barrier_hessian(double d, double dhat);

/// Barrier keeping a pressure inside [0, p_max], active within `margin` of either bound.
struct PressureBarrier {
  double max_pressure, margin;
  double value(double p) const { return barrier(p, margin) + barrier(max_pressure - p, margin); }
  double gradient(double p) const { return barrier_gradient(p, margin) - barrier_gradient(max_pressure - p, margin); }
};

} // namespace fibermold
