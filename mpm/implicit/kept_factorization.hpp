#pragma once
// The factorised tangent an implicit run keeps from step to step (docs/implicit.md, "Fewer
// factorisations"): the linear solver, the key of the unknowns it was made for, the matrix (a
// checkpoint stores it), and Newton's two ways to solve with it: its own step, or GMRES on the
// current tangent preconditioned by it ("Krylov on the kept factorisation"), bordered under
// indirect control.
#include <Eigen/Sparse>

#include "mpm/implicit/attempt.hpp"
#include "mpm/implicit/linear_solver.hpp"

namespace ecm::mpm {

// Indirect control's border of a step's system: [K, ku; c, cPrescribed] [d; dl] = [r; g], and
// y = -K0^-1 ku on the kept factorisation K0.
struct Border {
  const Eigen::VectorXd& ku;
  const Eigen::VectorXd& c;
  double cPrescribed;
  const Eigen::VectorXd& y;
  double g;
};

class KeptFactorization {
 public:
  KeptFactorization(LinearSolverKind kind, double krylovTolerance, int krylovIterations);
  void setThreads(int threads) { lu_.setThreads(threads); }

  // Whether the factorisation is of the unknowns `key` names (ImplicitSolver::factorKey()).
  bool isOf(long key) const { return key_ >= 0 && key_ == key; }
  // Factorises k over the unknowns `key` names (false: singular), timed and counted in `report`.
  // `reduction`: the change of unknowns (platens, ties) k is over, or null.
  bool factorize(const Eigen::SparseMatrix<double>& k, long key, const DofMap& dofs, const UnknownReduction* reduction,
                 ImplicitStepReport& report);
  Eigen::VectorXd solve(const Eigen::VectorXd& b, ImplicitStepReport& report);
  // Whether Newton's step may be GMRES on the current tangent (an exact factorisation to
  // precondition it, and Krylov vectors allowed).
  bool krylovOn() const { return krylovIterations_ > 0 && lu_.solvesExactly(); }
  // Newton's step on the current tangent k by GMRES preconditioned with the kept factorisation;
  // with a border the system is [k, ku; c, cP] [d; dl] = [r; g], preconditioned by the same border
  // on the kept factorisation: M^-1 [p; q] = [x + dl y; dl], x = K0^-1 p, y = -K0^-1 ku, dl from the
  // border's row. False where GMRES needs more than krylovIterations vectors: then the caller
  // factorises.
  bool krylovStep(const Eigen::SparseMatrix<double>& k, const Border* border, const Eigen::VectorXd& r,
                  ImplicitStepReport& report, Eigen::VectorXd& d, double* dl);

  // The factorised matrix and whether it is over reduced unknowns (for checkpoints).
  const Eigen::SparseMatrix<double>& matrix() const { return factored_; }
  bool reduced() const { return reduced_; }
  // A restart: factorises a saved matrix as the one of `key` (false: singular).
  bool restore(const Eigen::SparseMatrix<double>& k, bool reduced, long key, const DofMap& dofs,
               const UnknownReduction* reduction);
  // Nothing kept (the next factorisation analyses its pattern afresh).
  void forget();
  const LinearSolver& linearSolver() const { return lu_; }

 private:
  LinearSolver lu_;
  double krylovTolerance_;
  int krylovIterations_;
  long key_ = -1;                          // the unknowns' key of the factorisation (-1: none)
  Eigen::SparseMatrix<double> factored_;  // that tangent
  bool reduced_ = false;
};

}  // namespace ecm::mpm
