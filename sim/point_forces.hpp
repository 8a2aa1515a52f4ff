#pragma once
// The inner kernels of the elastic energy's value and gradient at one quadrature point q with
// shape-function entries k (nodes i_k, gradients ∇N_k):
//   F_q = Σ_k x_{i_k} ∇N_kᵀ                  (the deformation gradient, paper eq. 4)
//   ∂E/∂x_{i_k} += V_q P(F_q) ∇N_k           (the point's nodal forces)
// Two implementations with the same arithmetic: a portable one, and one with AVX2 and FMA chosen at
// run time when the processor has them (stiffness_simd_available()).

#include <Eigen/Core>

namespace fibermold {

/// F = Σ_k x_{nodes[k]} dN[k]ᵀ over `count` entries; `x` stacks positions as 3n.
Eigen::Matrix3d gather_deformation_gradient(const double* x, const int* nodes, const Eigen::Vector3d* dN, int count,
                                            bool simd = true);

/// g_{nodes[k]} += VP dN[k] over `count` entries; `g` stacks gradients as 3n.
void scatter_point_forces(const Eigen::Matrix3d& VP, const int* nodes, const Eigen::Vector3d* dN, int count, double* g,
                          bool simd = true);

} // namespace fibermold
