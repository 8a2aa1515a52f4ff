#include "sim/cholmod_solver.hpp"

#include <Eigen/CholmodSupport>

namespace fibermold {

struct CholmodSolver::Impl {
  Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower> llt;
  std::vector<int> outer, inner;  ///< the pattern last analyzed
};

CholmodSolver::CholmodSolver() : impl_(std::make_unique<Impl>())
{
  impl_->llt.cholmod().print = 0;  // "not positive definite" is an answer here, not an error to print
}
CholmodSolver::~CholmodSolver() = default;

bool CholmodSolver::factorize(const Eigen::SparseMatrix<double>& A, double shift)
{
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

} // namespace fibermold
