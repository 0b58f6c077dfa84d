#pragma once
// The sparse solver of the implicit steps (docs/implicit.md): the tangent is not symmetric once
// bands soften, so an LU, or GMRES preconditioned by algebraic multigrid (AmgSolver, where the
// build has hypre; "factorising" then hands it the tangent, and it decides when to rebuild its
// hierarchy). UMFPACK (SuiteSparse) when the build found it, Eigen's
// SparseLU otherwise; both analyse a pattern once (it is kept while the particles' stencils stay
// on the same nodes) and factorise when the Newton iteration asks. UMFPACK's shared library (and
// the BLAS, LAPACK and Fortran run-time it needs, some 3.5 MB resident) is loaded at its first
// use (mpm/implicit/umfpack_library.hpp), so that an explicit run does not carry it.
//
// The kind is chosen once, when the solver is made (each kind is a backend:
// mpm/implicit/linear_solver_backend.hpp); callers ask what it can do, never which it is.
#include <Eigen/SparseCore>
#include <memory>
#include <optional>
#include <vector>

#include "mpm/scene/solver_settings.hpp"
#include "mpm/implicit/amg_solver.hpp"

namespace ecm::mpm {

// (LinearSolverKind and available(): mpm/scene/solver_settings.hpp.)

// What the caller sets on a solver; the backends read it when they need it.
struct LinearSolverOptions {
  double iterativeTolerance = 1e-8;  // the AMG solver's GMRES (the LUs solve exactly)
  int copyAfter = 1;                 // UMFPACK: the solve from which its factors are copied by runs (0: never)
  int threads = 1;                   // UMFPACK: threads of the solves with the copied factors
};

class LinearSolverBackend;  // mpm/implicit/linear_solver_backend.hpp

class LinearSolver {
 public:
  explicit LinearSolver(LinearSolverKind kind);
  ~LinearSolver();
  LinearSolver(const LinearSolver&) = delete;
  LinearSolver& operator=(const LinearSolver&) = delete;

  // Factorises K (its pattern analysed at the first call, and after forgetPattern()); false if K is singular.
  bool factorize(const Eigen::SparseMatrix<double>& k);
  // The next K has another pattern.
  void forgetPattern();
  // x = K^-1 b. With UMFPACK, from the copyAfter-th solve with a factorisation on, by its factors
  // copied by runs (mpm/implicit/factor_runs.hpp: the same factors, a faster solve); with AMG, to
  // the iterative tolerance.
  Eigen::VectorXd solve(const Eigen::VectorXd& b);
  // Whether solve() is exact (an LU): its factors can then precondition Krylov steps on later
  // tangents. False for AMG, which solves to the iterative tolerance.
  bool solvesExactly() const;
  // Whether the solver needs each unknown's displacement component (setComponents): AMG does.
  bool needsComponents() const;
  // Each unknown's displacement component (0 x, 1 y), for the AMG solver; the LUs ignore it.
  void setComponents(std::vector<int> components);
  // 0: never copy (every solve is UMFPACK's own).
  void setCopyAfter(int solves) { options_.copyAfter = solves; }
  // Threads for the solves with the copied factors (mpm/implicit/factor_runs.hpp): two where there
  // are two or more, and the factors split.
  void setThreads(int threads) { options_.threads = threads; }
  // The relative residual to which the AMG solver's GMRES solves (ImplicitSettings::krylovTolerance;
  // the LUs solve exactly).
  void setIterativeTolerance(double tolerance) { options_.iterativeTolerance = tolerance; }
  // How many factorisations were copied by runs: UMFPACK's count, none for the others.
  std::optional<long> factorCopies() const;
  // The AMG solver's counts (linear_solver: amg, once it has solved), null for the LUs.
  const AmgStatistics* amgStatistics() const;

 private:
  LinearSolverOptions options_;
  std::unique_ptr<LinearSolverBackend> backend_;
};

}  // namespace ecm::mpm
