#include "sim/point_forces.hpp"
#include "sim/stiffness_column.hpp"

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#include <immintrin.h>
#define FIBERMOLD_POINT_FORCES_AVX2 1
#endif

namespace fibermold {

namespace {

Eigen::Matrix3d gather_portable(const double* x, const int* nodes, const Eigen::Vector3d* dN, int count)
{
  // Nine scalar sums: Eigen's outer-product update went through the stack at every node.
  double f[3][3] = {};
  for (int k = 0; k < count; ++k) {
    const double* xi = x + 3 * nodes[k];
    const double* g = dN[k].data();
    for (int a = 0; a < 3; ++a)
      for (int c = 0; c < 3; ++c) f[a][c] += xi[a] * g[c];
  }
  Eigen::Matrix3d F;
  for (int a = 0; a < 3; ++a)
    for (int c = 0; c < 3; ++c) F(a, c) = f[a][c];
  return F;
}

void scatter_portable(const Eigen::Matrix3d& VP, const int* nodes, const Eigen::Vector3d* dN, int count, double* g)
{
  for (int k = 0; k < count; ++k) {
    double* gi = g + 3 * nodes[k];
    const double* d = dN[k].data();
    for (int a = 0; a < 3; ++a) gi[a] += VP(a, 0) * d[0] + VP(a, 1) * d[1] + VP(a, 2) * d[2];
  }
}

#ifdef FIBERMOLD_POINT_FORCES_AVX2
// A column c of F (or of VP) holds its three rows a in the lanes of one register, the fourth lane
// zero. x_i is read with a masked load: the last node's fourth lane would be past the end of x.
// Two sets of sums, for even and odd entries, halve the chain of dependent FMAs.
__attribute__((target("avx2,fma"))) Eigen::Matrix3d gather_avx2(const double* x, const int* nodes,
                                                                const Eigen::Vector3d* dN, int count)
{
  const __m256i three = _mm256_set_epi64x(0, -1, -1, -1);
  __m256d f[2][3];
  for (auto& sums : f)
    for (auto& column : sums) column = _mm256_setzero_pd();
  int k = 0;
  for (; k + 1 < count; k += 2)
    for (int e = 0; e < 2; ++e) {
      const __m256d xi = _mm256_maskload_pd(x + 3 * nodes[k + e], three);
      const double* g = dN[k + e].data();
      for (int c = 0; c < 3; ++c) f[e][c] = _mm256_fmadd_pd(xi, _mm256_broadcast_sd(g + c), f[e][c]);
    }
  if (k < count) {
    const __m256d xi = _mm256_maskload_pd(x + 3 * nodes[k], three);
    const double* g = dN[k].data();
    for (int c = 0; c < 3; ++c) f[0][c] = _mm256_fmadd_pd(xi, _mm256_broadcast_sd(g + c), f[0][c]);
  }
  alignas(32) double column[3][4];
  for (int c = 0; c < 3; ++c) _mm256_store_pd(column[c], _mm256_add_pd(f[0][c], f[1][c]));
  Eigen::Matrix3d F;
  for (int a = 0; a < 3; ++a)
    for (int c = 0; c < 3; ++c) F(a, c) = column[c][a];
  return F;
}

// Each node's three entries are read and written as exactly those three (a 128-bit and a 64-bit
// access), as in stiffness_column.cpp: a 4-wide store would touch the next node's first entry.
__attribute__((target("avx2,fma"))) void scatter_avx2(const Eigen::Matrix3d& VP, const int* nodes,
                                                      const Eigen::Vector3d* dN, int count, double* g)
{
  const __m256i three = _mm256_set_epi64x(0, -1, -1, -1);
  // Eigen's 3 × 3 is column-major: column c starts at VP.data() + 3c.
  const __m256d c0 = _mm256_maskload_pd(VP.data(), three), c1 = _mm256_maskload_pd(VP.data() + 3, three),
                c2 = _mm256_maskload_pd(VP.data() + 6, three);
  for (int k = 0; k < count; ++k) {
    const double* d = dN[k].data();
    __m256d add = _mm256_mul_pd(c0, _mm256_broadcast_sd(d));
    add = _mm256_fmadd_pd(c1, _mm256_broadcast_sd(d + 1), add);
    add = _mm256_fmadd_pd(c2, _mm256_broadcast_sd(d + 2), add);
    double* p = g + 3 * nodes[k];
    _mm_storeu_pd(p, _mm_add_pd(_mm_loadu_pd(p), _mm256_castpd256_pd128(add)));
    _mm_store_sd(p + 2, _mm_add_sd(_mm_load_sd(p + 2), _mm256_extractf128_pd(add, 1)));
  }
}
#endif

} // namespace

Eigen::Matrix3d gather_deformation_gradient(const double* x, const int* nodes, const Eigen::Vector3d* dN, int count,
                                            bool simd)
{
#ifdef FIBERMOLD_POINT_FORCES_AVX2
  if (simd && stiffness_simd_available()) return gather_avx2(x, nodes, dN, count);
#endif
  return gather_portable(x, nodes, dN, count);
}

void scatter_point_forces(const Eigen::Matrix3d& VP, const int* nodes, const Eigen::Vector3d* dN, int count, double* g,
                          bool simd)
{
#ifdef FIBERMOLD_POINT_FORCES_AVX2
  if (simd && stiffness_simd_available()) return scatter_avx2(VP, nodes, dN, count, g);
#endif
  scatter_portable(VP, nodes, dN, count, g);
}

} // namespace fibermold
