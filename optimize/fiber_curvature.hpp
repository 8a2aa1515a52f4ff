#pragma once
// The curvature regularizer of section V-B: the squared curvature of a fiber integrated over its
// length,  R = ∫ κ² ds = ∫ |p' × p''|² / |p'|⁵ dt,  with its gradient in the spline's points and
// tangents (p' and p'' are linear in them). 5-point Gauss–Legendre per span.

#include "sim/hermite_spline.hpp"
#include "sim/muscle_energy.hpp"

namespace fibermold {

double fiber_curvature(const HermiteSpline& spline);
/// ∂R/∂(points, tangents); the pressure entry is 0.
FiberParameterGradient fiber_curvature_gradient(const HermiteSpline& spline);

} // namespace fibermold
