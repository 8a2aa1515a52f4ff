#include "sim/cholmod_solver.hpp"

#include <algorithm>
#include <cstdlib>

#include <dlfcn.h>

#include <Eigen/CholmodSupport>

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
/// 18.9 Gflop) factorizes in 0.33 s instead of 0.55 s. The examples' bodies at their own meshes
/// stay on one thread (the recovery bar's 1.0 Gflop is the largest), except the gripper finger's
/// (4.9 Gflop). A user's OPENBLAS_NUM_THREADS is left alone; another BLAS is not touched. The
/// kernel OpenBLAS picks for the CPU (OPENBLAS_CORETYPE) still rounds its own way:
/// docs/optimize.md, "The same design on other machines", gives what that moves.
constexpr double kTwoThreadFlops = 2e9;

void blas_threads(int threads)
{
  using SetThreads = void (*)(int);
  static const SetThreads set = []() -> SetThreads {
    if (std::getenv("OPENBLAS_NUM_THREADS")) return nullptr;
    return reinterpret_cast<SetThreads>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"));
  }();
  if (set) set(threads);
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
} // namespace

struct CholmodSolver::Impl {
  Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Upper> llt;
  std::vector<int> outer, inner; ///< the pattern last analyzed
  int threads = 1;               ///< BLAS threads for that pattern's factor (kTwoThreadFlops)
};

CholmodSolver::CholmodSolver() : impl_(std::make_unique<Impl>())
{
  blas_threads(1);
  impl_->llt.cholmod().print = 0; // "not positive definite" is an answer here, not an error to print
}
CholmodSolver::~CholmodSolver() = default;

bool CholmodSolver::factorize(const Eigen::SparseMatrix<double>& A, double shift)
{
  no_openmp_regions();
  const auto n = A.outerSize();
  const bool same = static_cast<Eigen::Index>(impl_->outer.size()) == n + 1 &&
                    std::equal(impl_->outer.begin(), impl_->outer.end(), A.outerIndexPtr()) &&
                    std::equal(impl_->inner.begin(), impl_->inner.end(), A.innerIndexPtr());
  if (!same) {
    impl_->llt.analyzePattern(A);
    impl_->outer.assign(A.outerIndexPtr(), A.outerIndexPtr() + n + 1);
    impl_->inner.assign(A.innerIndexPtr(), A.innerIndexPtr() + A.nonZeros());
    ++analyses_;
    impl_->threads = impl_->llt.cholmod().fl >= kTwoThreadFlops ? 2 : 1; // the analysis's flop count
  }
  blas_threads(impl_->threads);
  impl_->llt.setShift(shift);
  impl_->llt.factorize(A);
  return impl_->llt.info() == Eigen::Success;
}

double CholmodSolver::flops() const { return impl_->llt.cholmod().fl; }

Eigen::VectorXd CholmodSolver::solve(const Eigen::VectorXd& b) const
{
  blas_threads(impl_->threads); // another solver may have factorized since
  return impl_->llt.solve(b);
}

Eigen::MatrixXd CholmodSolver::solve(const Eigen::MatrixXd& B) const
{
  blas_threads(impl_->threads);
  return impl_->llt.solve(B);
}

} // namespace fibermold
