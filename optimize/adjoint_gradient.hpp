#pragma once
// Gradients through equilibrium by the adjoint method (paper eq. 9):
//   df/d(s, p) = −∂f/∂x H⁻¹ ∂²E_act/∂x∂(s, p) = −λᵀ ∂²E_act/∂x∂(s, p),   H λ = ∂f/∂x,
// one extra solve with the Hessian at the converged state per target.

#include <stdexcept>
#include <vector>

#include "sim/muscle_energy.hpp"
#include "sim/simulation.hpp"

namespace fibermold {

/// df/d(points, tangents, pressure) of each muscle for f(x*(s, p)), given ∂f/∂x at the equilibrium x*.
/// Throws std::runtime_error when the Hessian at x* is not positive definite (an unstable state).
std::vector<FiberParameterGradient> adjoint_gradient(Simulation& sim, const Eigen::VectorXd& x,
                                                     const Eigen::VectorXd& df_dx,
                                                     const std::vector<const MuscleEnergy*>& muscles);

} // namespace fibermold
