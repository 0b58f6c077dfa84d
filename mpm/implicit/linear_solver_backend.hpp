#pragma once
// One kind of linear solver behind LinearSolver (mpm/implicit/linear_solver.hpp): Eigen's
// SparseLU and the AMG solver (mpm/implicit/linear_solver.cpp), UMFPACK
// (mpm/implicit/umfpack_solver.cpp). makeLinearSolverBackend is the one place a kind becomes one.
#include <Eigen/SparseCore>
#include <algorithm>
#include <memory>
#include <optional>
#include <vector>

#include "mpm/implicit/linear_solver.hpp"

namespace ecm::mpm {

class LinearSolverBackend {
 public:
  virtual ~LinearSolverBackend() = default;
  virtual bool factorize(const Eigen::SparseMatrix<double>& k) = 0;
  virtual void forgetPattern() = 0;
  virtual Eigen::VectorXd solve(const Eigen::VectorXd& b) = 0;
  virtual bool solvesExactly() const { return true; }
  virtual bool needsComponents() const { return false; }
  virtual void setComponents(std::vector<int>) {}
  virtual std::optional<long> factorCopies() const { return std::nullopt; }
  virtual const AmgStatistics* amgStatistics() const { return nullptr; }
};

// `options` outlives the backend (the LinearSolver holds both).
std::unique_ptr<LinearSolverBackend> makeLinearSolverBackend(LinearSolverKind kind, const LinearSolverOptions& options);
#ifdef ECM_HAVE_UMFPACK
std::unique_ptr<LinearSolverBackend> makeUmfpackBackend(const LinearSolverOptions& options);
#endif

// K's pattern with every value 1: the analysis (ordering, strategy) then depends on the pattern
// only, not on which K of that pattern came first, so a restarted run factorises as the
// uninterrupted one did.
inline Eigen::SparseMatrix<double> patternOnes(const Eigen::SparseMatrix<double>& k) {
  Eigen::SparseMatrix<double> m = k;
  std::fill(m.valuePtr(), m.valuePtr() + m.nonZeros(), 1.0);
  return m;
}

}  // namespace ecm::mpm
