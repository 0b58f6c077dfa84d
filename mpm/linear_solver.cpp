#include "mpm/linear_solver.hpp"

namespace ecm::mpm {

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
      umfpack_.analyzePattern(k);
      analysed_ = true;
    }
    umfpack_.factorize(k);
    return umfpack_.info() == Eigen::Success;
  }
#endif
  if (!analysed_) lu_.analyzePattern(k), analysed_ = true;
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
