#pragma once
// The sparse direct solver of the implicit steps (docs/implicit.md): the tangent is not
// symmetric once bands soften, so an LU. UMFPACK (SuiteSparse) when the build found it, Eigen's
// SparseLU otherwise; both analyse a pattern once (it is kept while the particles' stencils stay
// on the same nodes) and factorise when the Newton iteration asks. UMFPACK's shared library (and
// the BLAS, LAPACK and Fortran run-time it needs, some 3.5 MB resident) is loaded at its first
// use (mpm/implicit/umfpack_library.hpp), so that an explicit run does not carry it.
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>
#include <memory>

#include "mpm/scene/solver_settings.hpp"

namespace ecm::mpm {

// (LinearSolverKind and available(): mpm/scene/solver_settings.hpp.)

struct UmfpackFactors;  // UMFPACK's symbolic and numeric factors (mpm/implicit/linear_solver.cpp)

class LinearSolver {
 public:
  explicit LinearSolver(LinearSolverKind kind);
  ~LinearSolver();
  // Factorises K (its pattern analysed at the first call, and after forgetPattern()); false if K is singular.
  bool factorize(const Eigen::SparseMatrix<double>& k);
  // The next K has another pattern.
  void forgetPattern() { analysed_ = false; }
  Eigen::VectorXd solve(const Eigen::VectorXd& b);

 private:
  LinearSolverKind kind_;
  bool analysed_ = false;
  Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> lu_;
  std::unique_ptr<UmfpackFactors> umfpack_;
};

}  // namespace ecm::mpm
