#pragma once
// The sparse solver of the implicit steps (docs/implicit.md): the tangent is not symmetric once
// bands soften, so an LU, or GMRES preconditioned by algebraic multigrid (AmgSolver, where the
// build has hypre; "factorising" then hands it the tangent, and it decides when to rebuild its
// hierarchy). UMFPACK (SuiteSparse) when the build found it, Eigen's
// SparseLU otherwise; both analyse a pattern once (it is kept while the particles' stencils stay
// on the same nodes) and factorise when the Newton iteration asks. UMFPACK's shared library (and
// the BLAS, LAPACK and Fortran run-time it needs, some 3.5 MB resident) is loaded at its first
// use (mpm/implicit/umfpack_library.hpp), so that an explicit run does not carry it.
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>
#include <memory>
#include <vector>

#include "mpm/scene/solver_settings.hpp"
#include "mpm/implicit/amg_solver.hpp"

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
  void forgetPattern();
  // Each unknown's displacement component (0 x, 1 y), for the AMG solver; the LUs do not need it.
  void setComponents(std::vector<int> components);
  // x = K^-1 b. With UMFPACK, from the copyAfter-th solve with a factorisation on, by its factors
  // copied by runs (mpm/implicit/factor_runs.hpp: the same factors, a faster solve); with AMG, to
  // the iterative tolerance.
  Eigen::VectorXd solve(const Eigen::VectorXd& b);
  // 0: never copy (every solve is UMFPACK's own).
  void setCopyAfter(int solves) { copyAfter_ = solves; }
  // Threads for the solves with the copied factors (mpm/implicit/factor_runs.hpp): two where there
  // are two or more, and the factors split.
  void setThreads(int threads) { threads_ = threads; }
  // How many factorisations were copied by runs.
  long factorCopies() const;
  // The relative residual to which the AMG solver's GMRES solves (ImplicitSettings::krylovTolerance;
  // the LUs solve exactly).
  void setIterativeTolerance(double tolerance) { iterativeTolerance_ = tolerance; }
  // The AMG solver's counts (linear_solver: amg), null for the LUs.
  const AmgStatistics* amgStatistics() const;

 private:
  LinearSolverKind kind_;
  bool analysed_ = false;
  double iterativeTolerance_ = 1e-8;
  int copyAfter_ = 1;
  int threads_ = 1;
  Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> lu_;
  std::unique_ptr<UmfpackFactors> umfpack_;
#ifdef ECM_HAVE_HYPRE
  std::unique_ptr<AmgSolver> amg_;
#endif
};

}  // namespace ecm::mpm
