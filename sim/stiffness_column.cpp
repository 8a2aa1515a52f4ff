#include "sim/stiffness_column.hpp"

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#include <immintrin.h>
#define FIBERMOLD_STIFFNESS_AVX2 1
#endif

namespace fibermold {

namespace {

int layout_index(int b, int d, int c, int a) { return ((3 * b + d) * 3 + c) * 3 + a; }

// H_ij[a][b] += Σ_c ∇N_i,c T[b][a][c] for the point's nodes i.
void add_contraction_portable(const double (&T)[3][3][3], const Eigen::Vector3d* gi, const int* nodes, int count,
                              const StiffnessColumn& column)
{
  for (int n = 0; n < count; ++n) {
    const double* g = gi[n].data();
    double* block = column.values + column.position[nodes[n]];
    for (int b = 0; b < 3; ++b)
      for (int a = 0; a < 3; ++a)
        block[b * column.stride + a] += g[0] * T[b][a][0] + g[1] * T[b][a][1] + g[2] * T[b][a][2];
  }
}

// T[b][a][c] = Σ_d V C[3a+c][3b+d] ∇N_j,d, then H_ij[a][b] += Σ_c ∇N_i,c T[b][a][c].
void add_point_portable(const double* W, const Eigen::Vector3d& gj, const Eigen::Vector3d* gi, const int* nodes,
                        int count, const StiffnessColumn& column)
{
  double T[3][3][3];
  for (int b = 0; b < 3; ++b)
    for (int c = 0; c < 3; ++c)
      for (int a = 0; a < 3; ++a)
        T[b][a][c] = W[layout_index(b, 0, c, a)] * gj[0] + W[layout_index(b, 1, c, a)] * gj[1] +
                     W[layout_index(b, 2, c, a)] * gj[2];
  add_contraction_portable(T, gi, nodes, count, column);
}

void add_neo_hookean_point_portable(const NeoHookeanPoint& p, const Eigen::Vector3d& gj, const Eigen::Vector3d* gi,
                                    const int* nodes, int count, const StiffnessColumn& column)
{
  const Eigen::Vector3d w = p.G * gj;
  double T[3][3][3];
  for (int b = 0; b < 3; ++b)
    for (int a = 0; a < 3; ++a)
      for (int c = 0; c < 3; ++c)
        T[b][a][c] = (a == b ? p.mu * gj[c] : 0.0) + p.lambda * p.G(a, c) * w[b] + p.c * p.G(b, c) * w[a];
  add_contraction_portable(T, gi, nodes, count, column);
}

#ifdef FIBERMOLD_STIFFNESS_AVX2
// The same with the three rows a of a block column in the lanes of one register (the fourth lane
// is zero: the loads of W are masked). In the matrix's storage a block column is read and written
// as exactly its three entries: 4-wide stores that overlapped the next node's entries measured
// slower (a partly overlapping load cannot be forwarded from the store buffer) and would write
// outside the column. A padded column takes one 4-wide load and store per block column instead:
// the exact Hessian of the 4×-DoF twisting bar (assembly_bench) 51–55 → 42–48 ms.
__attribute__((target("avx2,fma"))) inline void add_contraction_avx2(const __m256d (&T)[3][3],
                                                                     const Eigen::Vector3d* gi, const int* nodes,
                                                                     int count, const StiffnessColumn& column)
{
  // Locals: the stores below may alias anything (the intrinsics' types say so), the column's fields too.
  const std::ptrdiff_t stride = column.stride;
  double* const values = column.values;
  const int* const position = column.position;
  if (column.padded) {
    for (int n = 0; n < count; ++n) {
      const double* g = gi[n].data();
      const __m256d x = _mm256_broadcast_sd(g), y = _mm256_broadcast_sd(g + 1), z = _mm256_broadcast_sd(g + 2);
      double* block = values + position[nodes[n]];
      for (int b = 0; b < 3; ++b) {
        __m256d add = _mm256_fmadd_pd(T[b][0], x, _mm256_loadu_pd(block + b * stride));
        add = _mm256_fmadd_pd(T[b][1], y, add);
        _mm256_storeu_pd(block + b * stride, _mm256_fmadd_pd(T[b][2], z, add));
      }
    }
    return;
  }
  for (int n = 0; n < count; ++n) {
    const double* g = gi[n].data();
    const __m256d x = _mm256_broadcast_sd(g), y = _mm256_broadcast_sd(g + 1), z = _mm256_broadcast_sd(g + 2);
    double* block = values + position[nodes[n]];
    for (int b = 0; b < 3; ++b) {
      __m256d add = _mm256_mul_pd(T[b][0], x);
      add = _mm256_fmadd_pd(T[b][1], y, add);
      add = _mm256_fmadd_pd(T[b][2], z, add);
      double* p = block + b * stride;
      const __m128d lo = _mm_add_pd(_mm_loadu_pd(p), _mm256_castpd256_pd128(add));
      const __m128d hi = _mm_add_sd(_mm_load_sd(p + 2), _mm256_extractf128_pd(add, 1));
      _mm_storeu_pd(p, lo);
      _mm_store_sd(p + 2, hi);
    }
  }
}

__attribute__((target("avx2,fma"))) void add_point_avx2(const double* W, const Eigen::Vector3d& gj,
                                                        const Eigen::Vector3d* gi, const int* nodes, int count,
                                                        const StiffnessColumn& column)
{
  const __m256d gx = _mm256_set1_pd(gj[0]), gy = _mm256_set1_pd(gj[1]), gz = _mm256_set1_pd(gj[2]);
  const __m256i three = _mm256_set_epi64x(0, -1, -1, -1);
  __m256d T[3][3];
  for (int b = 0; b < 3; ++b)
    for (int c = 0; c < 3; ++c) {
      T[b][c] = _mm256_mul_pd(_mm256_maskload_pd(W + layout_index(b, 0, c, 0), three), gx);
      T[b][c] = _mm256_fmadd_pd(_mm256_maskload_pd(W + layout_index(b, 1, c, 0), three), gy, T[b][c]);
      T[b][c] = _mm256_fmadd_pd(_mm256_maskload_pd(W + layout_index(b, 2, c, 0), three), gz, T[b][c]);
    }
  add_contraction_avx2(T, gi, nodes, count, column);
}

// T[b][c] (rows a in the lanes) = Vμ ∇N_j,c e_b + Vλ w_b G[:, c] + Vc G_bc w, w = G ∇N_j.
__attribute__((target("avx2,fma"))) void add_neo_hookean_point_avx2(const NeoHookeanPoint& p, const Eigen::Vector3d& gj,
                                                                    const Eigen::Vector3d* gi, const int* nodes,
                                                                    int count, const StiffnessColumn& column)
{
  const __m256i three = _mm256_set_epi64x(0, -1, -1, -1);
  const double* G = p.G.data();
  const __m256d column0 = _mm256_maskload_pd(G, three), column1 = _mm256_maskload_pd(G + 3, three),
                column2 = _mm256_maskload_pd(G + 6, three);
  const __m256d Gc[3] = {column0, column1, column2};
  __m256d w = _mm256_mul_pd(column0, _mm256_set1_pd(gj[0]));
  w = _mm256_fmadd_pd(column1, _mm256_set1_pd(gj[1]), w);
  w = _mm256_fmadd_pd(column2, _mm256_set1_pd(gj[2]), w);
  alignas(32) double wb[4];
  _mm256_store_pd(wb, w);
  const __m256d e[3] = {_mm256_set_pd(0, 0, 0, 1), _mm256_set_pd(0, 0, 1, 0), _mm256_set_pd(0, 1, 0, 0)};
  __m256d T[3][3];
  for (int b = 0; b < 3; ++b) {
    const __m256d lambda_w = _mm256_set1_pd(p.lambda * wb[b]);
    for (int c = 0; c < 3; ++c) {
      T[b][c] = _mm256_mul_pd(_mm256_set1_pd(p.c * G[3 * c + b]), w);
      T[b][c] = _mm256_fmadd_pd(lambda_w, Gc[c], T[b][c]);
      T[b][c] = _mm256_fmadd_pd(e[b], _mm256_set1_pd(p.mu * gj[c]), T[b][c]);
    }
  }
  add_contraction_avx2(T, gi, nodes, count, column);
}
#endif

} // namespace

StiffnessLayout stiffness_layout(const Eigen::Matrix<double, 9, 9>& VC)
{
  StiffnessLayout W;
  for (int b = 0; b < 3; ++b)
    for (int d = 0; d < 3; ++d)
      for (int c = 0; c < 3; ++c)
        for (int a = 0; a < 3; ++a) W[layout_index(b, d, c, a)] = VC(3 * a + c, 3 * b + d);
  return W;
}

void add_neo_hookean_point_to_column(const NeoHookeanPoint& p, const Eigen::Vector3d& gj, const Eigen::Vector3d* gi,
                                     const int* nodes, int count, const StiffnessColumn& column, bool simd)
{
#ifdef FIBERMOLD_STIFFNESS_AVX2
  if (simd && stiffness_simd_available()) return add_neo_hookean_point_avx2(p, gj, gi, nodes, count, column);
#endif
  add_neo_hookean_point_portable(p, gj, gi, nodes, count, column);
}

bool stiffness_simd_available()
{
#ifdef FIBERMOLD_STIFFNESS_AVX2
  static const bool available = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
  return available;
#else
  return false;
#endif
}

void add_point_to_column(const double* W, const Eigen::Vector3d& gj, const Eigen::Vector3d* gi, const int* nodes,
                         int count, const StiffnessColumn& column, bool simd)
{
#ifdef FIBERMOLD_STIFFNESS_AVX2
  if (simd && stiffness_simd_available()) return add_point_avx2(W, gj, gi, nodes, count, column);
#endif
  add_point_portable(W, gj, gi, nodes, count, column);
}

} // namespace fibermold
