#include "mpm/implicit/amg_solver.hpp"

#include <HYPRE.h>
#include <HYPRE_krylov.h>
#include <HYPRE_parcsr_ls.h>
#include <mpi.h>
#include <omp.h>

#include <cstdlib>
#include <new>
#include <numeric>
#include <stdexcept>
#include <vector>

namespace ecm::mpm {

namespace {

// hypre runs on MPI; a run of ecm-mpm is one process, MPI's singleton (no mpirun needed).
void initialiseOnce() {
  static const bool done = [] {
    int initialised = 0;
    MPI_Initialized(&initialised);
    if (!initialised) {
      MPI_Init(nullptr, nullptr);
      std::atexit([] {
        int finalised = 0;
        MPI_Finalized(&finalised);
        if (!finalised) MPI_Finalize();
      });
    }
    HYPRE_Init();
    return true;
  }();
  (void)done;
}

// A vector of n values in hypre's IJ form.
struct IJVector {
  HYPRE_IJVector ij = nullptr;
  HYPRE_ParVector par = nullptr;
  explicit IJVector(HYPRE_Int n) {
    HYPRE_IJVectorCreate(MPI_COMM_WORLD, 0, n - 1, &ij);
    HYPRE_IJVectorSetObjectType(ij, HYPRE_PARCSR);
    HYPRE_IJVectorInitialize(ij);
    HYPRE_IJVectorAssemble(ij);
    HYPRE_IJVectorGetObject(ij, reinterpret_cast<void**>(&par));
  }
  ~IJVector() { HYPRE_IJVectorDestroy(ij); }
  IJVector(const IJVector&) = delete;
  IJVector& operator=(const IJVector&) = delete;
  void set(const Eigen::VectorXd& v, std::vector<HYPRE_BigInt>& index) {
    HYPRE_IJVectorSetValues(ij, static_cast<HYPRE_Int>(v.size()), index.data(), v.data());
  }
  void get(Eigen::VectorXd& v, std::vector<HYPRE_BigInt>& index) const {
    HYPRE_IJVectorGetValues(ij, static_cast<HYPRE_Int>(v.size()), index.data(), v.data());
  }
};

// A square sparse matrix in hypre's IJ (ParCSR) form, from Eigen's compressed columns.
struct IJMatrix {
  HYPRE_IJMatrix ij = nullptr;
  HYPRE_ParCSRMatrix par = nullptr;
  explicit IJMatrix(const Eigen::SparseMatrix<double>& k) {
    const Eigen::SparseMatrix<double, Eigen::RowMajor> rows = k;
    const auto n = static_cast<HYPRE_Int>(k.rows());
    HYPRE_IJMatrixCreate(MPI_COMM_WORLD, 0, n - 1, 0, n - 1, &ij);
    HYPRE_IJMatrixSetObjectType(ij, HYPRE_PARCSR);
    std::vector<HYPRE_Int> perRow(static_cast<std::size_t>(n));
    for (HYPRE_Int i = 0; i < n; ++i) perRow[static_cast<std::size_t>(i)] = static_cast<HYPRE_Int>(rows.outerIndexPtr()[i + 1] - rows.outerIndexPtr()[i]);
    HYPRE_IJMatrixSetRowSizes(ij, perRow.data());
    HYPRE_IJMatrixInitialize(ij);
    std::vector<HYPRE_BigInt> rowIndex(static_cast<std::size_t>(n)), columns(rows.innerIndexPtr(), rows.innerIndexPtr() + rows.nonZeros());
    std::iota(rowIndex.begin(), rowIndex.end(), HYPRE_BigInt{0});
    HYPRE_IJMatrixSetValues(ij, n, perRow.data(), rowIndex.data(), columns.data(), rows.valuePtr());
    HYPRE_IJMatrixAssemble(ij);
    HYPRE_IJMatrixGetObject(ij, reinterpret_cast<void**>(&par));
  }
  ~IJMatrix() { HYPRE_IJMatrixDestroy(ij); }
  IJMatrix(const IJMatrix&) = delete;
  IJMatrix& operator=(const IJMatrix&) = delete;
};

}  // namespace

struct AmgSolver::Hypre {
  HYPRE_Int n = 0;
  std::unique_ptr<IJMatrix> current;    // the tangent the solves use
  std::unique_ptr<IJMatrix> hierarchy;  // the tangent the hierarchy was built on (kept: its levels refer to it)
  std::unique_ptr<IJVector> b, x;
  std::vector<HYPRE_BigInt> index;
  HYPRE_Solver amg = nullptr, gmres = nullptr;

  void destroySolvers() {
    if (gmres) HYPRE_ParCSRGMRESDestroy(gmres), gmres = nullptr;
    if (amg) HYPRE_BoomerAMGDestroy(amg), amg = nullptr;
  }
  ~Hypre() { destroySolvers(); }
};

AmgSolver::AmgSolver() : h_(std::make_unique<Hypre>()) { initialiseOnce(); }
AmgSolver::~AmgSolver() = default;

void AmgSolver::forget() {
  h_->destroySolvers();
  h_->hierarchy.reset();
  stale_ = true;
}

void AmgSolver::setMatrix(const Eigen::SparseMatrix<double>& k) {
  const auto n = static_cast<HYPRE_Int>(k.rows());
  if (n != h_->n) {
    forget();
    h_->n = n;
    h_->b = std::make_unique<IJVector>(n);
    h_->x = std::make_unique<IJVector>(n);
    h_->index.resize(static_cast<std::size_t>(n));
    std::iota(h_->index.begin(), h_->index.end(), HYPRE_BigInt{0});
  }
  h_->current = std::make_unique<IJMatrix>(k);
  if (!h_->amg) stale_ = true;
}

void AmgSolver::setup() {
  const double start = omp_get_wtime();
  h_->destroySolvers();
  if (!h_->current) h_->current = std::move(h_->hierarchy);  // rebuilt on the same tangent
  h_->hierarchy.reset();
  HYPRE_BoomerAMGCreate(&h_->amg);
  HYPRE_BoomerAMGSetPrintLevel(h_->amg, 0);
  HYPRE_BoomerAMGSetCoarsenType(h_->amg, 10);     // HMIS
  HYPRE_BoomerAMGSetInterpType(h_->amg, 6);       // extended+i
  HYPRE_BoomerAMGSetPMaxElmts(h_->amg, 4);
  HYPRE_BoomerAMGSetStrongThreshold(h_->amg, options.strongThreshold);
  if (options.aggressiveLevels > 0) HYPRE_BoomerAMGSetAggNumLevels(h_->amg, options.aggressiveLevels);
  if (components_.size() == static_cast<std::size_t>(h_->n)) {
    // hypre takes the array and frees it with the hierarchy.
    auto* functions = static_cast<HYPRE_Int*>(std::malloc(sizeof(HYPRE_Int) * components_.size()));
    if (!functions) throw std::bad_alloc();
    for (std::size_t i = 0; i < components_.size(); ++i) functions[i] = components_[i];
    HYPRE_BoomerAMGSetNumFunctions(h_->amg, 2);
    HYPRE_BoomerAMGSetDofFunc(h_->amg, functions);
  }
  HYPRE_BoomerAMGSetRelaxType(h_->amg, options.relaxType);
  HYPRE_BoomerAMGSetNumSweeps(h_->amg, options.sweeps);
  if (options.iluLevels > 0) {  // ILU(0) on the finest levels: 21-50 % fewer GMRES iterations on softened tangents (coarse, medium DEN)
    HYPRE_BoomerAMGSetSmoothType(h_->amg, 5);
    HYPRE_BoomerAMGSetSmoothNumLevels(h_->amg, options.iluLevels);
  }
  HYPRE_BoomerAMGSetMaxIter(h_->amg, 1);          // one V-cycle per preconditioning
  HYPRE_BoomerAMGSetTol(h_->amg, 0.0);
  HYPRE_ParCSRGMRESCreate(MPI_COMM_WORLD, &h_->gmres);
  HYPRE_GMRESSetKDim(h_->gmres, options.krylovDimension);
  HYPRE_GMRESSetMaxIter(h_->gmres, maxIterations);
  HYPRE_GMRESSetTol(h_->gmres, tolerance);
  HYPRE_GMRESSetPrintLevel(h_->gmres, 0);
  HYPRE_GMRESSetPrecond(h_->gmres, reinterpret_cast<HYPRE_PtrToSolverFcn>(HYPRE_BoomerAMGSolve),
                        reinterpret_cast<HYPRE_PtrToSolverFcn>(HYPRE_BoomerAMGSetup), h_->amg);
  HYPRE_ParCSRGMRESSetup(h_->gmres, h_->current->par, h_->b->par, h_->x->par);
  h_->hierarchy = std::move(h_->current);
  h_->current.reset();
  stale_ = false;
  freshIterations_ = -1;
  stats_.setups++;
  stats_.setupSeconds += omp_get_wtime() - start;
}

bool AmgSolver::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  for (int attempt = 0;; ++attempt) {
    if (stale_) setup();
    const double start = omp_get_wtime();
    HYPRE_ParCSRMatrix k = h_->current ? h_->current->par : h_->hierarchy->par;
    h_->b->set(b, h_->index);
    x = Eigen::VectorXd::Zero(b.size());
    h_->x->set(x, h_->index);
    HYPRE_ClearAllErrors();
    HYPRE_ParCSRGMRESSolve(h_->gmres, k, h_->b->par, h_->x->par);
    HYPRE_Int iterations = 0, converged = 0;
    HYPRE_GMRESGetNumIterations(h_->gmres, &iterations);
    HYPRE_GMRESGetConverged(h_->gmres, &converged);
    HYPRE_ClearAllErrors();  // a solve that did not converge is answered below, not by hypre's error flag
    h_->x->get(x, h_->index);
    lastIterations_ = iterations;
    if (freshIterations_ < 0) freshIterations_ = iterations;
    stats_.solves++;
    stats_.iterations += iterations;
    stats_.solveSeconds += omp_get_wtime() - start;
    if (converged) {
      if (iterations > rebuildIterations()) stale_ = true;
      return true;
    }
    if (attempt > 0 || !h_->current) {
      stats_.failedSolves++;
      return false;
    }
    stale_ = true;  // a fresh hierarchy on the current tangent, once
  }
}

}  // namespace ecm::mpm
