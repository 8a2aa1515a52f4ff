#include "optimize/adjoint_gradient.hpp"

namespace fibermold {

std::vector<FiberParameterGradient> adjoint_gradient(Simulation& sim, const Eigen::VectorXd& x,
                                                     const Eigen::VectorXd& df_dx,
                                                     const std::vector<const MuscleEnergy*>& muscles)
{
  Eigen::VectorXd lambda;
  if (!sim.solver().solve_with_hessian(x, df_dx, lambda))
    throw std::runtime_error("the Hessian at the equilibrium is not positive definite: no adjoint gradient");
  std::vector<FiberParameterGradient> out;
  for (const MuscleEnergy* m : muscles) {
    FiberParameterGradient g = m->mixed_derivative(x, lambda);
    for (auto& v : g.points) v = -v;
    for (auto& v : g.tangents) v = -v;
    g.pressure = -g.pressure;
    out.push_back(std::move(g));
  }
  return out;
}

} // namespace fibermold
