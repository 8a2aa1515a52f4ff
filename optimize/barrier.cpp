#include "optimize/barrier.hpp"

#include <cmath>

namespace fibermold {

double barrier(double d, double dhat)
{
  if (d <= 0) return HUGE_VAL;
  if (d >= dhat) return 0;
  return -(d - dhat) * (d - dhat) * std::log(d / dhat);
}

double barrier_gradient(double d, double dhat)
{
  if (d <= 0 || d >= dhat) return 0;
  // b'(d) = −2(d − d̂) ln(d/d̂) − (d − d̂)²/d = (d̂ − d)(2 ln(d/d̂) − d̂/d + 1)
  return (dhat - d) * (2 * std::log(d / dhat) - dhat / d + 1);
}

double barrier_hessian(double d, double dhat)
{
  if (d <= 0 || d >= dhat) return 0;
  // b''(d) = −2 ln(d/d̂) − 4(d − d̂)/d + (d − d̂)²/d² = −2 ln(d/d̂) − (d − d̂)(3d + d̂)/d²
  return -2 * std::log(d / dhat) - (d - dhat) * (3 * d + dhat) / (d * d);
}

} // namespace fibermold
