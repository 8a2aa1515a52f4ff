#pragma once
// The inner kernel of the elastic Hessian assembly: one quadrature point's contribution to one
// node column j of the stiffness,
//   H_ij[a][b] += Σ_{c,d} V C[3a+c][3b+d] ∇N_i,c ∇N_j,d   for the point's nodes i ≤ j,
// where V C = V ∂P/∂F is the point's 9 × 9 stress derivative. Two implementations with the same
// arithmetic: a portable one, and one with AVX2 and FMA (4 doubles per instruction) chosen at run
// time when the processor has them.

#include <cstddef>

#include <Eigen/Core>

namespace fibermold {

/// The point's V ∂P/∂F in the order the kernel reads: entry (b, d, c, a) = V C[3a+c][3b+d] at
/// ((3b + d)·3 + c)·3 + a.
using StiffnessLayout = Eigen::Matrix<double, 81, 1>;
StiffnessLayout stiffness_layout(const Eigen::Matrix<double, 9, 9>& VC);

/// Block (i, j) entry (a, b) is at values[b · stride + position[i] + a].
struct StiffnessColumn {
  double* values;        ///< SparseHessian::column_values(j), or a padded copy
  std::ptrdiff_t stride; ///< 3 · |neighbours(j)| (padded: 4 ·)
  const int* position;   ///< node → 3 · (its index among j's neighbours) (padded: 4 ·)
  /// Each block column has a fourth entry, unused: the AVX2 kernels then read and write a block
  /// column as one 4-wide access instead of a 2-wide and a 1-wide one.
  bool padded = false;
};

/// Adds the point with layout `W` to `column` for the `count` nodes `nodes` (gradients `gi`),
/// coupled to node j (gradient `gj`). `simd` selects the AVX2 kernel when the processor has it.
void add_point_to_column(const double* W, const Eigen::Vector3d& gj, const Eigen::Vector3d* gi, const int* nodes,
                         int count, const StiffnessColumn& column, bool simd = true);

/// The exact Neo-Hookean stress derivative at a point in the 12 numbers it is made of:
///   V ∂P_ac/∂F_bd = Vμ δ_ab δ_cd + Vλ G_ac G_bd + Vc G_ad G_bc,  G = F⁻ᵀ, c = μ − λ ln J
/// (neo_hookean.hpp). 12 doubles instead of the layout's 81: the assembly reads each point once per
/// node column it touches, and at 30 nodes per point those reads are most of its memory traffic.
struct NeoHookeanPoint {
  Eigen::Matrix3d G;    ///< F⁻ᵀ, column-major
  double mu, lambda, c; ///< V μ, V λ, V (μ − λ ln J)
};

/// The same sum as add_point_to_column with W = stiffness_layout(V ∂P/∂F) of that point, with
/// T[b][a][c] = Σ_d V ∂P_ac/∂F_bd ∇N_j,d = Vμ δ_ab ∇N_j,c + Vλ G_ac (G∇N_j)_b + Vc G_bc (G∇N_j)_a
/// formed from those 12 numbers.
void add_neo_hookean_point_to_column(const NeoHookeanPoint& p, const Eigen::Vector3d& gj, const Eigen::Vector3d* gi,
                                     const int* nodes, int count, const StiffnessColumn& column, bool simd = true);

/// Whether `add_point_to_column(..., simd = true)` runs the AVX2 kernel on this processor.
bool stiffness_simd_available();

} // namespace fibermold
