#include "sim/cholmod_solver.hpp"

#include <algorithm>
#include <cstdlib>
#include <thread>

#include <dlfcn.h>

#include <Eigen/CholmodSupport>

namespace fibermold {

namespace {
/// OpenBLAS (Debian's default BLAS under CHOLMOD) keeps its worker threads spinning on
/// sched_yield for about 0.1 s after each call, and on 2 cores they took that time from the
/// assembly's oneTBB threads when every BLAS call had 2 threads (session 9: bench/sim's twisting
/// bar 4.2 → 3.6–4.0 s with one). So BLAS runs on one thread, except inside a factorization: there
/// all cores serve it, as nothing else runs meanwhile (session 14, bench/sim, per factorization:
/// the bar at the paper's tet count 0.035–0.050 → 0.029–0.043 s in six runs each way, the 4 mm
/// cantilever 0.090–0.098 → 0.070–0.073 s and the fem-p2 cantilever 0.178–0.181 → 0.146–0.176 s
/// in three; the assemblies after them no slower). A user's OPENBLAS_NUM_THREADS is left alone; another BLAS is
/// not touched.
class BlasThreads {
public:
  static const BlasThreads& get()
  {
    static const BlasThreads threads;
    return threads;
  }
  /// All cores for BLAS while it lives.
  struct Factorizing {
    Factorizing() { get().use(get().cores_); }
    ~Factorizing() { get().use(1); }
    Factorizing(const Factorizing&) = delete;
    Factorizing& operator=(const Factorizing&) = delete;
  };

private:
  using SetThreads = void (*)(int);
  BlasThreads()
  {
    if (std::getenv("OPENBLAS_NUM_THREADS")) return;
    set_ = reinterpret_cast<SetThreads>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"));
    cores_ = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    if (set_) set_(1);
  }
  void use(int threads) const
  {
    if (set_) set_(threads);
  }
  SetThreads set_ = nullptr;
  int cores_ = 1;
};

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
  std::vector<int> outer, inner;  ///< the pattern last analyzed
};

CholmodSolver::CholmodSolver() : impl_(std::make_unique<Impl>())
{
  BlasThreads::get();
  impl_->llt.cholmod().print = 0;  // "not positive definite" is an answer here, not an error to print
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
  {
    const BlasThreads::Factorizing all_cores;
    impl_->llt.factorize(A);
  }
  return impl_->llt.info() == Eigen::Success;
}

Eigen::VectorXd CholmodSolver::solve(const Eigen::VectorXd& b) const { return impl_->llt.solve(b); }

} // namespace fibermold
