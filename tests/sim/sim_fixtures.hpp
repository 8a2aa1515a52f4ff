#pragma once
// Small meshes for the sim tests.

#include <cmath>
#include <vector>

#include <Eigen/Sparse>

#include "mesh/tetrahedralize.hpp"
#include "primitives.hpp"

namespace fibermold::test {

/// A tetrahedralized box [lo, hi] with edges about `edge`; `quadratic` for 10-node tets.
inline TetMesh box_mesh(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, double edge, bool quadratic = false)
{
  const Eigen::Vector3d size = hi - lo;
  const Eigen::Vector3i cells = (size / edge).array().round().cast<int>().max(1);
  SurfaceMesh surface = box(lo, hi, cells);
  NullProgress progress;
  return tetrahedralize(surface, {edge, 1.5, 10, quadratic}, progress);
}

/// The twisting bar (129 × 20 × 20 mm along +x, centred on the x axis) with its skin a 4.3 mm grid
/// and tets of `edge` (m): 8 mm gives about the paper's tet count (2,754 tets, 2,433 DoFs).
inline TetMesh skin_grid_twisting_bar(double edge)
{
  NullProgress progress;
  return tetrahedralize(box({0, -0.01, -0.01}, {0.129, 0.01, 0.01}, Eigen::Vector3i(30, 5, 5)), {edge, 1.5, 10, false},
                        progress);
}

/// The twisting bar at 4× the example's DoFs: 6 mm edges (3,851 tets, 2,922 DoFs). The example used
/// this mesh before session 12; the benches keep it so that their figures compare across sessions.
inline TetMesh fine_twisting_bar() { return skin_grid_twisting_bar(0.006); }

/// Control points of a helical fiber along +x from the origin to (length, 0, 0): `turns` turns of
/// `radius` (right-handed for handedness +1), 12 points in between.
inline std::vector<Eigen::Vector3d> helix_points(double length, double radius, double turns, double handedness)
{
  std::vector<Eigen::Vector3d> points{{0, 0, 0}};
  for (int k = 1; k <= 12; ++k) {
    const double a = handedness * 2 * M_PI * turns * k / 13;
    points.emplace_back(length * k / 13, radius * std::cos(a), radius * std::sin(a));
  }
  points.emplace_back(length, 0, 0);
  return points;
}

/// A stiffness-like matrix as wide as an MLS body's: 3 DoFs per node of an nx × ny × nz grid, each
/// node coupled to every node within `reach` grid steps, diagonally dominant.
inline Eigen::SparseMatrix<double> wide_stencil_matrix(int nx, int ny, int nz, int reach = 2)
{
  const auto node = [&](int i, int j, int k) { return (k * ny + j) * nx + i; };
  std::vector<Eigen::Triplet<double>> entries;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        for (int dk = -reach; dk <= reach; ++dk)
          for (int dj = -reach; dj <= reach; ++dj)
            for (int di = -reach; di <= reach; ++di) {
              const int a = i + di, b = j + dj, c = k + dk;
              if (a < 0 || b < 0 || c < 0 || a >= nx || b >= ny || c >= nz) continue;
              const int p = node(i, j, k), q = node(a, b, c);
              if (q < p) continue; // the upper triangle
              for (int r = 0; r < 3; ++r)
                for (int s = 0; s < 3; ++s) {
                  if (p == q && s < r) continue;
                  const double v = p == q ? (r == s ? 200.0 : 0.3) : -1.0 / (1 + di * di + dj * dj + dk * dk + r + s);
                  entries.emplace_back(3 * p + r, 3 * q + s, v);
                }
            }
  Eigen::SparseMatrix<double> A(3 * nx * ny * nz, 3 * nx * ny * nz);
  A.setFromTriplets(entries.begin(), entries.end());
  return A;
}

/// A with its nodes (3 coordinates each) renumbered: node i becomes node_of[i].
inline Eigen::SparseMatrix<double> renumbered(const Eigen::SparseMatrix<double>& A, const std::vector<int>& node_of)
{
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> P(A.rows());
  for (std::size_t i = 0; i < node_of.size(); ++i)
    for (int r = 0; r < 3; ++r) P.indices()[static_cast<Eigen::Index>(3 * i) + r] = 3 * node_of[i] + r;
  Eigen::SparseMatrix<double> upper(A.rows(), A.cols());
  upper.selfadjointView<Eigen::Upper>() = A.selfadjointView<Eigen::Upper>().twistedBy(P);
  // Each column's rows ascending, as CHOLMOD reads them through Eigen (the transposes sort them).
  const Eigen::SparseMatrix<double, Eigen::RowMajor> rows = upper;
  return Eigen::SparseMatrix<double>(rows);
}

} // namespace fibermold::test
