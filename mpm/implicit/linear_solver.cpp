#include "mpm/implicit/linear_solver.hpp"

#include <algorithm>
#include <array>

#ifdef ECM_HAVE_UMFPACK
#include "mpm/implicit/umfpack_library.hpp"
#endif

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

#ifdef ECM_HAVE_UMFPACK
struct UmfpackFactors {
  const UmfpackLibrary& lib = umfpackLibrary();
  std::array<double, UMFPACK_CONTROL> control{};
  std::array<double, UMFPACK_INFO> info{};
  void* symbolic = nullptr;
  void* numeric = nullptr;
  Eigen::SparseMatrix<double> k;  // the factorised matrix (compressed), which the solves pass on

  UmfpackFactors() {
    lib.defaults(control.data());
    // The symmetric strategy (AMD on K + K^T, diagonal pivots preferred): K is structurally
    // symmetric and nearly so in value. No iterative refinement: Newton corrects the solve.
    // Measured in bench/implicit_bench.cpp (docs/implicit.md).
    control[UMFPACK_STRATEGY] = UMFPACK_STRATEGY_SYMMETRIC;
    control[UMFPACK_IRSTEP] = 0;
  }
  ~UmfpackFactors() {
    if (numeric) lib.freeNumeric(&numeric);
    if (symbolic) lib.freeSymbolic(&symbolic);
  }
  UmfpackFactors(const UmfpackFactors&) = delete;
  UmfpackFactors& operator=(const UmfpackFactors&) = delete;

  bool analyse(const Eigen::SparseMatrix<double>& pattern) {
    if (numeric) lib.freeNumeric(&numeric);
    if (symbolic) lib.freeSymbolic(&symbolic);
    Eigen::SparseMatrix<double> m = ones(pattern);
    m.makeCompressed();
    return lib.symbolic(static_cast<int>(m.rows()), static_cast<int>(m.cols()), m.outerIndexPtr(), m.innerIndexPtr(),
                        m.valuePtr(), &symbolic, control.data(), info.data()) == UMFPACK_OK;
  }
  bool factorise(const Eigen::SparseMatrix<double>& matrix) {
    if (numeric) lib.freeNumeric(&numeric);
    k = matrix;
    k.makeCompressed();
    return lib.numeric(k.outerIndexPtr(), k.innerIndexPtr(), k.valuePtr(), symbolic, &numeric, control.data(),
                       info.data()) == UMFPACK_OK;
  }
  Eigen::VectorXd solve(const Eigen::VectorXd& b) {
    Eigen::VectorXd x(b.size());
    lib.solve(UMFPACK_A, k.outerIndexPtr(), k.innerIndexPtr(), k.valuePtr(), x.data(), b.data(), numeric,
              control.data(), info.data());
    return x;
  }
};
#else
struct UmfpackFactors {};
#endif

LinearSolver::LinearSolver(LinearSolverKind kind) : kind_(kind) {}
LinearSolver::~LinearSolver() = default;

void LinearSolver::forgetPattern() {
  analysed_ = false;
#ifdef ECM_HAVE_HYPRE
  if (amg_) amg_->forget();
#endif
}

const AmgStatistics* LinearSolver::amgStatistics() const {
#ifdef ECM_HAVE_HYPRE
  if (amg_) return &amg_->statistics();
#endif
  return nullptr;
}

void LinearSolver::setComponents([[maybe_unused]] std::vector<int> components) {
#ifdef ECM_HAVE_HYPRE
  if (kind_ == LinearSolverKind::Amg) {
    if (!amg_) amg_ = std::make_unique<AmgSolver>(), amg_->tolerance = iterativeTolerance_;
    amg_->setComponents(std::move(components));
  }
#endif
}

bool LinearSolver::factorize(const Eigen::SparseMatrix<double>& k) {
#ifdef ECM_HAVE_HYPRE
  if (kind_ == LinearSolverKind::Amg) {
    if (!amg_) amg_ = std::make_unique<AmgSolver>(), amg_->tolerance = iterativeTolerance_;
    amg_->setMatrix(k);
    return true;
  }
#endif
#ifdef ECM_HAVE_UMFPACK
  if (kind_ == LinearSolverKind::Umfpack) {
    if (!umfpack_) umfpack_ = std::make_unique<UmfpackFactors>();  // loads the library at the first use
    if (!analysed_) {
      if (!umfpack_->analyse(k)) return false;
      analysed_ = true;
    }
    return umfpack_->factorise(k);
  }
#endif
  if (!analysed_) lu_.analyzePattern(ones(k)), analysed_ = true;
  lu_.factorize(k);
  return lu_.info() == Eigen::Success;
}

Eigen::VectorXd LinearSolver::solve(const Eigen::VectorXd& b) {
#ifdef ECM_HAVE_HYPRE
  if (kind_ == LinearSolverKind::Amg) {
    Eigen::VectorXd x;
    amg_->solve(b, x);  // where GMRES fell short, Newton's residual says so
    return x;
  }
#endif
#ifdef ECM_HAVE_UMFPACK
  if (kind_ == LinearSolverKind::Umfpack) return umfpack_->solve(b);
#endif
  return lu_.solve(b);
}

}  // namespace ecm::mpm
