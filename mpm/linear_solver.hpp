#pragma once
// The sparse direct solver of the implicit steps (docs/implicit.md): the tangent is not
// symmetric once bands soften, so an LU. UMFPACK (SuiteSparse, through Eigen's wrapper) when the
// build found it, Eigen's SparseLU otherwise; both analyse a pattern once (it is kept while the
// particles' stencils stay on the same nodes) and factorise when the Newton iteration asks.
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>
#ifdef ECM_HAVE_UMFPACK
#include <Eigen/UmfPackSupport>
#endif

namespace ecm::mpm {

enum class LinearSolverKind { SparseLU, Umfpack };
const char* toString(LinearSolverKind k);
bool available(LinearSolverKind k);

class LinearSolver {
 public:
  explicit LinearSolver(LinearSolverKind kind) : kind_(kind) {}
  // Factorises K (its pattern analysed at the first call, and after forgetPattern()); false if K is singular.
  bool factorize(const Eigen::SparseMatrix<double>& k);
  // The next K has another pattern.
  void forgetPattern() { analysed_ = false; }
  Eigen::VectorXd solve(const Eigen::VectorXd& b);

 private:
  LinearSolverKind kind_;
  bool analysed_ = false;
  Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> lu_;
#ifdef ECM_HAVE_UMFPACK
  Eigen::UmfPackLU<Eigen::SparseMatrix<double>> umfpack_;
#endif
};

}  // namespace ecm::mpm
