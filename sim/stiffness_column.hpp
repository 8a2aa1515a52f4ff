#pragma once
// The inner kernel of the elastic Hessian assembly: one quadrature point's contribution to one
// node column j of the stiffness,
//   H_ij[a][b] += Σ_{c,d} V C[3a+c][3b+d] ∇N_i,c ∇N_j,d   for the point's nodes i ≥ j,
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

struct StiffnessColumn {
  double* values;        ///< SparseHessian::column_values(j)
  std::ptrdiff_t stride; ///< 3 · |neighbours(j)|
  const int* position;   ///< node → 3 · (its index among j's neighbours)
};

/// Adds the point with layout `W` to `column` for the `count` nodes `nodes` (gradients `gi`),
/// coupled to node j (gradient `gj`). `simd` selects the AVX2 kernel when the processor has it.
void add_point_to_column(const double* W, const Eigen::Vector3d& gj, const Eigen::Vector3d* gi, const int* nodes,
                         int count, const StiffnessColumn& column, bool simd = true);

/// Whether `add_point_to_column(..., simd = true)` runs the AVX2 kernel on this processor.
bool stiffness_simd_available();

} // namespace fibermold
