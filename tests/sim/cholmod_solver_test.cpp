// CholmodSolver: a large factorization runs BLAS on two threads whatever the machine, so that its
// bits are the same on one core as on many, and a small one on one (cholmod_solver.cpp,
// kTwoThreadFlops).
#include "sim/cholmod_solver.hpp"

#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include <dlfcn.h>
#include <gtest/gtest.h>
#include <sched.h>
#include <sys/wait.h>
#include <unistd.h>

namespace fibermold {
namespace {

/// A stiffness-like matrix as wide as an MLS body's: 3 DoFs per node of an nx × ny × nz grid, each
/// node coupled to every node within two grid steps, diagonally dominant.
Eigen::SparseMatrix<double> wide_stencil_matrix(int nx, int ny, int nz)
{
  const auto node = [&](int i, int j, int k) { return (k * ny + j) * nx + i; };
  std::vector<Eigen::Triplet<double>> entries;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        for (int dk = -2; dk <= 2; ++dk)
          for (int dj = -2; dj <= 2; ++dj)
            for (int di = -2; di <= 2; ++di) {
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

Eigen::VectorXd solve_once(const Eigen::SparseMatrix<double>& A, double* flops = nullptr)
{
  CholmodSolver solver;
  if (!solver.factorize(A)) return {};
  if (flops) *flops = solver.flops();
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(A.rows(), -1.0, 1.0);
  return solver.solve(b);
}

Eigen::SparseMatrix<double> large_matrix() { return wide_stencil_matrix(14, 14, 26); }

/// OpenBLAS's thread count now, where OpenBLAS is the BLAS; 0 otherwise.
int blas_threads_now()
{
  using Get = int (*)();
  const auto get = reinterpret_cast<Get>(dlsym(RTLD_DEFAULT, "openblas_get_num_threads"));
  return get ? get() : 0;
}

/// The child of the test below: a fresh process started on one core (OpenBLAS counts the cores it may
/// use when it loads, so a forked child would keep its parent's threads), which solves the large matrix
/// and writes the solution's bits to the descriptor its environment names, before any test runs.
const bool kOneCoreChild = [] {
  const char* fd = std::getenv("FIBERMOLD_ONE_CORE_BITS_FD");
  if (!fd) return false;
  const Eigen::VectorXd x = solve_once(large_matrix());
  const auto bytes = static_cast<std::size_t>(x.size()) * sizeof(double);
  const bool written = ::write(std::atoi(fd), x.data(), bytes) == static_cast<ssize_t>(bytes);
  ::_exit(written ? 0 : 2);
}();

TEST(CholmodSolver, ALargeFactorizationGivesTheSameBitsOnOneCoreAsOnAll)
{
  cpu_set_t allowed;
  CPU_ZERO(&allowed);
  ASSERT_EQ(::sched_getaffinity(0, sizeof allowed, &allowed), 0);
  if (CPU_COUNT(&allowed) < 2) GTEST_SKIP() << "one core: nothing to compare it with";
  const Eigen::SparseMatrix<double> A = large_matrix();
  double flops = 0;
  const Eigen::VectorXd all = solve_once(A, &flops);
  ASSERT_EQ(all.size(), A.rows());
  EXPECT_GT(flops, 2e9); // on two BLAS threads
  if (!std::getenv("OPENBLAS_NUM_THREADS") && blas_threads_now() > 0) {
    EXPECT_EQ(blas_threads_now(), 2);
  }
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(A.rows(), -1.0, 1.0);
  EXPECT_LT((A.selfadjointView<Eigen::Upper>() * all - b).norm(), 1e-10 * b.norm());

  int fds[2];
  ASSERT_EQ(::pipe(fds), 0);
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) { // this test program again, bound to the first core it may run on
    ::close(fds[0]);
    int first = 0;
    while (!CPU_ISSET(first, &allowed)) ++first;
    cpu_set_t one;
    CPU_ZERO(&one);
    CPU_SET(first, &one);
    if (::sched_setaffinity(0, sizeof one, &one) != 0) ::_exit(2);
    ::setenv("FIBERMOLD_ONE_CORE_BITS_FD", std::to_string(fds[1]).c_str(), 1);
    ::execl("/proc/self/exe", "cholmod-one-core", static_cast<char*>(nullptr));
    ::_exit(2);
  }
  ::close(fds[1]);
  std::vector<double> one_core(static_cast<std::size_t>(A.rows()));
  std::size_t got = 0;
  const std::size_t want = one_core.size() * sizeof(double);
  for (ssize_t n; got < want && (n = ::read(fds[0], reinterpret_cast<char*>(one_core.data()) + got, want - got)) > 0;)
    got += static_cast<std::size_t>(n);
  ::close(fds[0]);
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  ASSERT_EQ(got, want);
  EXPECT_EQ(std::memcmp(one_core.data(), all.data(), want), 0) << "the factorization rounds by the core count";
}

TEST(CholmodSolver, ASmallFactorizationRunsOnOneBlasThread)
{
  double flops = 0;
  ASSERT_EQ(solve_once(large_matrix()).size(), 3 * 14 * 14 * 26);
  ASSERT_EQ(solve_once(wide_stencil_matrix(6, 6, 6), &flops).size(), 3 * 216);
  EXPECT_GT(flops, 0);
  EXPECT_LT(flops, 2e9);
  if (!std::getenv("OPENBLAS_NUM_THREADS") && blas_threads_now() > 0) {
    EXPECT_EQ(blas_threads_now(), 1);
  }
}

} // namespace
} // namespace fibermold
