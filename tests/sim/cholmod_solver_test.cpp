// CholmodSolver: a large factorization runs BLAS on two threads whatever the machine, so that its
// bits are the same on one core as on many, and a small one on one (cholmod_solver.cpp,
// kTwoThreadFlops); a long body is factorized in the band ordering, a compact one in CHOLMOD's.
#include "sim/cholmod_solver.hpp"

#include <Eigen/CholmodSupport>

#include <cstdlib>
#include <cstring>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include <dlfcn.h>
#include <gtest/gtest.h>
#include <sched.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "sim_fixtures.hpp"

namespace fibermold {
namespace {
using test::wide_stencil_matrix;

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

/// Whether CholmodSolver stops OpenBLAS's workers after a two-thread call here: OpenBLAS's, with a
/// pool of at most 2 threads and no user's thread settings (cholmod_solver.cpp, stop_blas_workers).
bool workers_stopped_here()
{
  using Count = int (*)();
  const auto cores = reinterpret_cast<Count>(dlsym(RTLD_DEFAULT, "openblas_get_num_procs"));
  return cores && cores() <= 2 && !std::getenv("OPENBLAS_NUM_THREADS") && !std::getenv("OPENBLAS_THREAD_TIMEOUT") &&
         dlsym(RTLD_DEFAULT, "blas_thread_shutdown_");
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
  EXPECT_GT(flops, 2e9); // on two BLAS threads (and then back to one where the workers are stopped)
  if (!std::getenv("OPENBLAS_NUM_THREADS") && blas_threads_now() > 0) {
    EXPECT_EQ(blas_threads_now(), workers_stopped_here() ? 1 : 2);
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

/// The CPU time this process takes over `seconds` of sleep: its threads' spinning.
double cpu_seconds_while_asleep(double seconds)
{
  timespec a{}, b{};
  ::clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &a);
  ::usleep(static_cast<useconds_t>(seconds * 1e6));
  ::clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &b);
  return static_cast<double>(b.tv_sec - a.tv_sec) + 1e-9 * static_cast<double>(b.tv_nsec - a.tv_nsec);
}

TEST(CholmodSolver, BlasWorkersDoNotSpinAfterATwoThreadFactorizationAndStartAgainForTheNext)
{
  // OpenBLAS's workers spin for about 0.1 s after a threaded call (2^28 cycles), taking a core from
  // the assembly that follows; on up to 2 cores the solver stops them (cholmod_solver.cpp,
  // stop_blas_workers). Over 60 ms of sleep after a factorization, after a solve, after another
  // solver is made and after a one-thread factorization (setting OpenBLAS's thread count on a
  // stopped pool starts it again), the process takes under 15 ms of CPU (with them spinning: about
  // 60 ms). The next factorization starts them again and rounds alike.
  if (!workers_stopped_here()) GTEST_SKIP() << "not OpenBLAS, more than 2 cores, or the user's thread settings";
  const Eigen::SparseMatrix<double> A = large_matrix();
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(A.rows(), -1.0, 1.0);
  CholmodSolver solver;
  ASSERT_TRUE(solver.factorize(A));
  ASSERT_GT(solver.flops(), 2e9); // on two BLAS threads
  EXPECT_LT(cpu_seconds_while_asleep(0.06), 0.015) << "after a factorization";
  const Eigen::VectorXd first = solver.solve(b);
  EXPECT_LT(cpu_seconds_while_asleep(0.06), 0.015) << "after a solve";
  CholmodSolver small;
  EXPECT_LT(cpu_seconds_while_asleep(0.06), 0.015) << "after another solver is made";
  const Eigen::SparseMatrix<double> S = wide_stencil_matrix(4, 4, 4);
  ASSERT_TRUE(small.factorize(S));
  ASSERT_LT(small.flops(), 2e9);
  EXPECT_EQ(small.solve(Eigen::VectorXd(Eigen::VectorXd::Ones(S.rows()))).size(), S.rows());
  EXPECT_LT(cpu_seconds_while_asleep(0.06), 0.015) << "after a one-thread factorization and solve";
  ASSERT_TRUE(solver.factorize(A));
  const Eigen::VectorXd again = solver.solve(b);
  ASSERT_EQ(again.size(), first.size());
  EXPECT_EQ(std::memcmp(again.data(), first.data(), static_cast<std::size_t>(first.size()) * sizeof(double)), 0);
  EXPECT_LT((A.selfadjointView<Eigen::Upper>() * again - b).norm(), 1e-10 * b.norm());
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

/// The operations of CHOLMOD's factorization of A in its own ordering (AMD, or METIS).
double own_ordering_flops(const Eigen::SparseMatrix<double>& A)
{
  Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Upper> llt;
  llt.analyzePattern(A);
  return llt.cholmod().fl;
}

TEST(CholmodSolver, ALongBodyFactorizesInTheBandOrderingWithFewerOperations)
{
  // A bar of 6 × 5 × 30 nodes, each coupled to the nodes within 3 grid steps (as an MLS finger's
  // nodes reach about 3.4 edges): CHOLMOD's ordering counts 1.6 Gflop, the band ordering 0.26.
  // Its nodes shuffled, so that their numbering is no band ordering of its own.
  std::vector<int> node_of(6 * 5 * 30);
  std::iota(node_of.begin(), node_of.end(), 0);
  std::shuffle(node_of.begin(), node_of.end(), std::mt19937(11));
  const Eigen::SparseMatrix<double> A = test::renumbered(wide_stencil_matrix(6, 5, 30, 3), node_of);
  CholmodSolver solver;
  ASSERT_TRUE(solver.factorize(A));
  EXPECT_TRUE(solver.band_ordered());
  const double own = own_ordering_flops(A);
  EXPECT_LT(solver.flops(), 0.25 * own) << solver.flops() << " against " << own;
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(A.rows(), -1.0, 1.0);
  const Eigen::VectorXd x = solver.solve(b);
  EXPECT_LT((A.selfadjointView<Eigen::Upper>() * x - b).norm(), 1e-12 * b.norm());
  // Refactorized with a shift and solved for many right-hand sides at once, in the same ordering.
  ASSERT_TRUE(solver.factorize(A, 5.0));
  Eigen::MatrixXd B(A.rows(), 2);
  B << b, b.reverse();
  const Eigen::MatrixXd X = solver.solve(B);
  Eigen::SparseMatrix<double> shifted = A;
  for (Eigen::Index i = 0; i < A.rows(); ++i) shifted.coeffRef(i, i) += 5.0;
  EXPECT_LT((shifted.selfadjointView<Eigen::Upper>() * X - B).norm(), 1e-12 * B.norm());
  EXPECT_EQ(solver.analyses(), 1);
}

TEST(CholmodSolver, ACompactBodyKeepsCholmodsOwnOrdering)
{
  const Eigen::SparseMatrix<double> A = wide_stencil_matrix(9, 9, 9);
  CholmodSolver solver;
  ASSERT_TRUE(solver.factorize(A));
  EXPECT_FALSE(solver.band_ordered());
  EXPECT_EQ(solver.flops(), own_ordering_flops(A));
}

} // namespace
} // namespace fibermold
