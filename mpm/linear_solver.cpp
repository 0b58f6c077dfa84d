#include "mpm/linear_solver.hpp"

#include <algorithm>

namespace ecm::mpm {

namespace {

// K's pattern with every value 1: the analysis (ordering, strategy) then depends on the pattern
// only, not on which K of that pattern came first, so a restarted run factorises as the
// uninterrupted one did.
Eigen::SparseMatrix<double> ones(const Eigen::SparseMatrix<double>& k) {
  Eigen::SparseMatrix<double> m = k;
  std::fill(m.valuePtr(), m.valuePtr() + m.nonZeros(), 1.0);
  return m;
}

}  // namespace

const char* toString(LinearSolverKind k) { return k == LinearSolverKind::Umfpack ? "umfpack" : "sparselu"; }

bool available([[maybe_unused]] LinearSolverKind k) {
#ifdef ECM_HAVE_UMFPACK
  return true;
#else
  return k == LinearSolverKind::SparseLU;
#endif
}

bool LinearSolver::factorize(const Eigen::SparseMatrix<double>& k) {
#ifdef ECM_HAVE_UMFPACK
  if (kind_ == LinearSolverKind::Umfpack) {
    if (!analysed_) {
      // The symmetric strategy (AMD on K + K^T, diagonal pivots preferred): K is structurally
      // symmetric and nearly so in value. No iterative refinement: Newton corrects the solve.
      // Measured in bench/implicit_bench.cpp (docs/implicit.md).
      umfpack_.umfpackControl()(UMFPACK_STRATEGY) = UMFPACK_STRATEGY_SYMMETRIC;
      umfpack_.umfpackControl()(UMFPACK_IRSTEP) = 0;
      umfpack_.analyzePattern(ones(k));
      analysed_ = true;
    }
    umfpack_.factorize(k);
    return umfpack_.info() == Eigen::Success;
  }
#endif
  if (!analysed_) lu_.analyzePattern(ones(k)), analysed_ = true;
  lu_.factorize(k);
  return lu_.info() == Eigen::Success;
}

Eigen::VectorXd LinearSolver::solve(const Eigen::VectorXd& b) {
#ifdef ECM_HAVE_UMFPACK
  if (kind_ == LinearSolverKind::Umfpack) return umfpack_.solve(b);
#endif
  return lu_.solve(b);
}

}  // namespace ecm::mpm
