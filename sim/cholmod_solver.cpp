#include "sim/cholmod_solver.hpp"

#include <algorithm>
#include <atomic>
#include <cstdlib>

#include <dlfcn.h>

#include <Eigen/CholmodSupport>

#include "sim/band_ordering.hpp"

namespace fibermold {

namespace {
/// BLAS (under CHOLMOD's supernodal factorization) runs on a number of threads that the matrix
/// decides, never the machine: OpenBLAS splits dpotrf and dsyrk by its thread count, and the
/// rounding with them, so that a 2-core and a 64-core machine would otherwise optimize the same
/// design along different paths (session 16: the twisting bar's optimization took 382 iterations
/// with 2 BLAS threads, 374 with one). A factorization of fewer than kTwoThreadFlops (about 80 ms
/// on one thread) runs on one thread: there a second BLAS thread costs more than it saves, as its
/// spinning after each call takes a core from the assembly (session 9; the twisting bar optimized
/// in 12.6 s with two, 9.9 s with one). A larger one runs on two, also on a one-core machine (the
/// same rounding; there the threads take turns): the gripper finger at 3.4 mm (n = 11,652,
/// 18.9 Gflop in AMD's ordering) factorized in 0.33 s instead of 0.55 s in session 34. The
/// examples' bodies at their own meshes stay on one thread, except the gripper finger's (3.8 Gflop
/// in the band ordering). A user's OPENBLAS_NUM_THREADS is left alone; another BLAS is not touched. The
/// kernel OpenBLAS picks for the CPU (OPENBLAS_CORETYPE) still rounds its own way:
/// docs/optimize.md, "The same design on other machines", gives what that moves.
constexpr double kTwoThreadFlops = 2e9;

using SetThreads = void (*)(int);

/// OpenBLAS's openblas_set_num_threads; null for another BLAS or under a user's OPENBLAS_NUM_THREADS.
SetThreads openblas_set_threads()
{
  static const SetThreads set = []() -> SetThreads {
    if (std::getenv("OPENBLAS_NUM_THREADS")) return nullptr;
    return reinterpret_cast<SetThreads>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"));
  }();
  return set;
}

/// The count blas_threads last set (0: none yet). Setting OpenBLAS's count starts its workers again
/// where they were stopped (stop_blas_workers), so a count already set is not set again.
std::atomic<int> blas_threads_set{0};

void blas_threads(int threads)
{
  const SetThreads set = openblas_set_threads();
  if (!set || blas_threads_set.exchange(threads) == threads) return;
  set(threads);
}

/// OpenBLAS's worker threads spin on sched_yield for about 0.1 s after each threaded call before
/// they sleep (2^28 cycles, OPENBLAS_THREAD_TIMEOUT, read once when the library loads). On 2 cores
/// that spinning took a core from the assembly that follows a factorization: the gripper finger at
/// 3.4 mm, `bench/finger_speed` (session 49), 0.181 s per assembly with the workers left spinning,
/// 0.157 s with OPENBLAS_THREAD_TIMEOUT=4 (16 cycles), the factorization 0.261 and 0.259 s. So after a
/// two-thread factorization or solve the workers are stopped, as OpenBLAS itself stops them before
/// a fork (blas_thread_shutdown_); its next threaded call, or a count set, starts them again (tens
/// of µs, and up to a few ms of the next call). The count is set to 1 first, while the pool runs.
/// Only where OpenBLAS's pool is at most 2 threads (its count of the cores it may use): a larger
/// pool would start all its workers again at each call, all but one to spin with nothing to do,
/// and there a spinning worker takes one core of many. The split of the work, and so the rounding,
/// is the thread count's, not the pool's. Never while another thread is in BLAS: fibermold calls
/// BLAS (through CHOLMOD) from one thread at a time. A user's OPENBLAS_NUM_THREADS or
/// OPENBLAS_THREAD_TIMEOUT leaves the workers alone.
void stop_blas_workers()
{
  using Shutdown = int (*)();
  using Count = int (*)();
  static const Shutdown shutdown = []() -> Shutdown {
    if (!openblas_set_threads() || std::getenv("OPENBLAS_THREAD_TIMEOUT")) return nullptr;
    const auto cores = reinterpret_cast<Count>(dlsym(RTLD_DEFAULT, "openblas_get_num_procs"));
    if (!cores || cores() > 2) return nullptr;
    return reinterpret_cast<Shutdown>(dlsym(RTLD_DEFAULT, "blas_thread_shutdown_"));
  }();
  if (!shutdown) return;
  blas_threads(1);
  shutdown();
}

/// Debian's CHOLMOD is built with OpenMP and asks for 4 threads (CHOLMOD_OMP_NUM_THREADS, fixed
/// when the library was built) in the loops that copy A and the updates into each supernode: many
/// short parallel regions per factorization. On 2 cores the extra threads take turns through futex
/// waits; one thread does the copies faster. assembly_bench, the bar's Hessian (lnz 1.77 M,
/// 1.2 GFlop): 105–118 ms → 53–69 ms per factorization. Called on the thread that factorizes, as
/// the setting may be per thread; a user's OMP_THREAD_LIMIT or OMP_MAX_ACTIVE_LEVELS is left alone.
void no_openmp_regions()
{
  using SetLevels = void (*)(int);
  static const SetLevels set = []() -> SetLevels {
    if (std::getenv("OMP_THREAD_LIMIT") || std::getenv("OMP_MAX_ACTIVE_LEVELS")) return nullptr;
    return reinterpret_cast<SetLevels>(dlsym(RTLD_DEFAULT, "omp_set_max_active_levels"));
  }();
  if (set) set(0);
}

/// CHOLMOD's supernodal Cholesky through Eigen, which also analyzes in an ordering given
/// (cholmod_analyze_p with CHOLMOD_GIVEN): CHOLMOD then permutes and solves as with its own.
class SupernodalLLT : public Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Upper> {
public:
  SupernodalLLT() { cholmod().print = 0; } // "not positive definite" is an answer here, not an error to print

  /// order[k]: the row of A placed k-th.
  void analyze_pattern_in(const Eigen::SparseMatrix<double>& A, std::vector<int> order)
  {
    if (m_cholmodFactor) cholmod_free_factor(&m_cholmodFactor, &cholmod());
    cholmod_sparse view = Eigen::viewAsCholmod(A.selfadjointView<Eigen::Upper>());
    cholmod().nmethods = 1;
    cholmod().method[0].ordering = CHOLMOD_GIVEN;
    m_cholmodFactor = cholmod_analyze_p(&view, order.data(), nullptr, 0, &cholmod());
    cholmod().nmethods = 0; // CHOLMOD's default again (method[0] is the given ordering there too)
    m_isInitialized = true;
    m_info = m_cholmodFactor ? Eigen::Success : Eigen::NumericalIssue;
    m_analysisIsOk = m_cholmodFactor != nullptr;
    m_factorizationIsOk = false;
  }
};
} // namespace

struct CholmodSolver::Impl {
  std::unique_ptr<SupernodalLLT> llt = std::make_unique<SupernodalLLT>();
  std::vector<int> outer, inner; ///< the pattern last analyzed
  int threads = 1;               ///< BLAS threads for that pattern's factor (kTwoThreadFlops)
  bool band = false;             ///< that pattern is factorized in the band ordering

  void analyze(const Eigen::SparseMatrix<double>& A);
};

void CholmodSolver::Impl::analyze(const Eigen::SparseMatrix<double>& A)
{
  // CHOLMOD's own choice (AMD, or METIS where AMD fills much) and the band ordering: the one whose
  // factorization counts fewer operations is kept. The choice is the pattern's, so the same on
  // every machine that runs the same build.
  band = false;
  llt = std::make_unique<SupernodalLLT>();
  llt->analyzePattern(A);
  auto banded = std::make_unique<SupernodalLLT>();
  banded->analyze_pattern_in(A, band_ordering(A));
  if (!(banded->info() == Eigen::Success && banded->cholmod().fl < llt->cholmod().fl)) return;
  llt = std::move(banded);
  band = true;
}

CholmodSolver::CholmodSolver() : impl_(std::make_unique<Impl>()) { blas_threads(1); }
CholmodSolver::~CholmodSolver() = default;

bool CholmodSolver::factorize(const Eigen::SparseMatrix<double>& A, double shift)
{
  no_openmp_regions();
  const auto n = A.outerSize();
  const bool same = static_cast<Eigen::Index>(impl_->outer.size()) == n + 1 &&
                    std::equal(impl_->outer.begin(), impl_->outer.end(), A.outerIndexPtr()) &&
                    std::equal(impl_->inner.begin(), impl_->inner.end(), A.innerIndexPtr());
  if (!same) {
    impl_->analyze(A);
    impl_->outer.assign(A.outerIndexPtr(), A.outerIndexPtr() + n + 1);
    impl_->inner.assign(A.innerIndexPtr(), A.innerIndexPtr() + A.nonZeros());
    ++analyses_;
    impl_->threads = impl_->llt->cholmod().fl >= kTwoThreadFlops ? 2 : 1; // the analysis's flop count
  }
  blas_threads(impl_->threads);
  impl_->llt->setShift(shift);
  impl_->llt->factorize(A);
  if (impl_->threads > 1) stop_blas_workers();
  return impl_->llt->info() == Eigen::Success;
}

double CholmodSolver::flops() const { return impl_->llt->cholmod().fl; }

bool CholmodSolver::band_ordered() const { return impl_->band; }

Eigen::VectorXd CholmodSolver::solve(const Eigen::VectorXd& b) const
{
  blas_threads(impl_->threads); // another solver may have factorized since
  Eigen::VectorXd x = impl_->llt->solve(b);
  if (impl_->threads > 1) stop_blas_workers();
  return x;
}

Eigen::MatrixXd CholmodSolver::solve(const Eigen::MatrixXd& B) const
{
  blas_threads(impl_->threads);
  Eigen::MatrixXd X = impl_->llt->solve(B);
  if (impl_->threads > 1) stop_blas_workers();
  return X;
}

} // namespace fibermold
