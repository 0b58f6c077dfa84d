// The linear solver of the implicit steps (mpm/implicit/linear_solver.hpp): the facade, the kind
// chosen once (makeLinearSolverBackend), and the two small backends, Eigen's SparseLU and the
// AMG solver (UMFPACK's is mpm/implicit/umfpack_solver.cpp).
#include "mpm/implicit/linear_solver.hpp"

#include <Eigen/SparseLU>

#include "mpm/implicit/linear_solver_backend.hpp"

namespace ecm::mpm {

namespace {

class SparseLuBackend final : public LinearSolverBackend {
 public:
  bool factorize(const Eigen::SparseMatrix<double>& k) override {
    if (!analysed_) lu_.analyzePattern(patternOnes(k)), analysed_ = true;
    lu_.factorize(k);
    return lu_.info() == Eigen::Success;
  }
  void forgetPattern() override { analysed_ = false; }
  Eigen::VectorXd solve(const Eigen::VectorXd& b) override { return lu_.solve(b); }

 private:
  bool analysed_ = false;
  Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> lu_;
};

#ifdef ECM_HAVE_HYPRE
// GMRES preconditioned by BoomerAMG (mpm/implicit/amg_solver.hpp), made at the first use with the
// iterative tolerance set by then.
class AmgBackend final : public LinearSolverBackend {
 public:
  explicit AmgBackend(const LinearSolverOptions& options) : options_(options) {}
  bool factorize(const Eigen::SparseMatrix<double>& k) override {
    amg().setMatrix(k);
    return true;
  }
  void forgetPattern() override {
    if (amg_) amg_->forget();
  }
  Eigen::VectorXd solve(const Eigen::VectorXd& b) override {
    Eigen::VectorXd x;
    amg_->solve(b, x);  // where GMRES fell short, Newton's residual says so
    return x;
  }
  bool solvesExactly() const override { return false; }
  bool needsComponents() const override { return true; }
  void setComponents(std::vector<int> components) override { amg().setComponents(std::move(components)); }
  const AmgStatistics* amgStatistics() const override { return amg_ ? &amg_->statistics() : nullptr; }

 private:
  AmgSolver& amg() {
    if (!amg_) amg_ = std::make_unique<AmgSolver>(), amg_->tolerance = options_.iterativeTolerance;
    return *amg_;
  }
  const LinearSolverOptions& options_;
  std::unique_ptr<AmgSolver> amg_;
};
#endif

}  // namespace

std::unique_ptr<LinearSolverBackend> makeLinearSolverBackend(LinearSolverKind kind, [[maybe_unused]] const LinearSolverOptions& options) {
  switch (kind) {
    case LinearSolverKind::Amg:
#ifdef ECM_HAVE_HYPRE
      return std::make_unique<AmgBackend>(options);
#else
      break;  // (Scene::validate refuses it in a build without hypre)
#endif
    case LinearSolverKind::Umfpack:
#ifdef ECM_HAVE_UMFPACK
      return makeUmfpackBackend(options);
#else
      break;
#endif
    case LinearSolverKind::SparseLU: break;
  }
  return std::make_unique<SparseLuBackend>();
}

LinearSolver::LinearSolver(LinearSolverKind kind) : backend_(makeLinearSolverBackend(kind, options_)) {}
LinearSolver::~LinearSolver() = default;

bool LinearSolver::factorize(const Eigen::SparseMatrix<double>& k) { return backend_->factorize(k); }
void LinearSolver::forgetPattern() { backend_->forgetPattern(); }
Eigen::VectorXd LinearSolver::solve(const Eigen::VectorXd& b) { return backend_->solve(b); }
bool LinearSolver::solvesExactly() const { return backend_->solvesExactly(); }
bool LinearSolver::needsComponents() const { return backend_->needsComponents(); }
void LinearSolver::setComponents(std::vector<int> components) { backend_->setComponents(std::move(components)); }
std::optional<long> LinearSolver::factorCopies() const { return backend_->factorCopies(); }
const AmgStatistics* LinearSolver::amgStatistics() const { return backend_->amgStatistics(); }

}  // namespace ecm::mpm
