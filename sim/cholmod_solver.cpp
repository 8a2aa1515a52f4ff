#include "sim/cholmod_solver.hpp"

#include <algorithm>
#include <cstdlib>

#include <dlfcn.h>

#include <Eigen/CholmodSupport>

namespace fibermold {

namespace {
/// BLAS (under CHOLMOD's supernodal factorization) runs on one thread, on every machine: OpenBLAS
/// splits dpotrf and dsyrk by its thread count, and the rounding with them, so that a 2-core and a
/// 64-core machine would optimize the same design along different paths (session 16: the twisting
/// bar's optimization took 382 iterations with 2 BLAS threads, 374 with one, surface RMSE 1.073 and
/// 1.081 mm). One thread costs little here: the assembly runs on all cores through oneTBB, and with
/// two BLAS threads their spinning took the assembly's time (session 9); inside a factorization
/// two threads saved 10–25 % of it (session 14). A user's OPENBLAS_NUM_THREADS is left alone; another
/// BLAS is not touched. The kernel OpenBLAS picks for the CPU (OPENBLAS_CORETYPE) still rounds its
/// own way: docs/optimize.md, "The same design on other machines", gives what that moves.
void one_blas_thread()
{
  static const bool done = [] {
    if (std::getenv("OPENBLAS_NUM_THREADS")) return false;
    using SetThreads = void (*)(int);
    const auto set = reinterpret_cast<SetThreads>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"));
    if (set) set(1);
    return set != nullptr;
  }();
  (void)done;
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
};

CholmodSolver::CholmodSolver() : impl_(std::make_unique<Impl>())
{
  one_blas_thread();
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
  }
  impl_->llt.setShift(shift);
  impl_->llt.factorize(A);
  return impl_->llt.info() == Eigen::Success;
}

Eigen::VectorXd CholmodSolver::solve(const Eigen::VectorXd& b) const { return impl_->llt.solve(b); }
Eigen::MatrixXd CholmodSolver::solve(const Eigen::MatrixXd& B) const { return impl_->llt.solve(B); }

} // namespace fibermold
