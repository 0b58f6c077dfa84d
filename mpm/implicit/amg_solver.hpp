#pragma once
// The iterative alternative to the sparse LU (docs/implicit.md, "The AMG solver"): GMRES on the
// implicit tangent, preconditioned by hypre's BoomerAMG (algebraic multigrid, the two
// displacement components of a node kept together). The tangent is not symmetric once bands
// soften, hence GMRES. The multigrid hierarchy is the expensive part; it is built for one tangent
// and kept for the tangents that follow (the fine level is always the current tangent) until the
// GMRES iterations it costs say that it no longer serves. Built only when the build found hypre
// (ECM_HAVE_HYPRE).
#include <Eigen/SparseCore>
#include <memory>
#include <vector>

namespace ecm::mpm {

// BoomerAMG's choices (docs/implicit.md, "The AMG solver"): the defaults are the ones measured
// there; bench_implicit's BM_Amg* compare others on the DEN tangents.
struct AmgOptions {
  double strongThreshold = 0.5;  // a connection is strong above this share of the row's largest
  int aggressiveLevels = 0;      // levels coarsened aggressively (fewer, cheaper levels)
  int relaxType = 6;             // on the levels below iluLevels: 6 symmetric hybrid Gauss-Seidel, 8 l1 GS, 18 l1-Jacobi
  int sweeps = 1;                // smoothing sweeps down and up
  int iluLevels = 1;             // the finest levels smoothed by ILU(0) instead (hypre's ParILUK); 0: none
  int krylovDimension = 50;      // GMRES's restart
};

struct AmgStatistics {
  long setups = 0;        // hierarchies built
  long solves = 0;        // GMRES solves
  long iterations = 0;    // GMRES iterations, all solves
  long failedSolves = 0;  // solves that did not reach the tolerance (even after a fresh hierarchy)
  double setupSeconds = 0.0, solveSeconds = 0.0;
};

class AmgSolver {
 public:
  AmgSolver();
  ~AmgSolver();
  AmgSolver(const AmgSolver&) = delete;
  AmgSolver& operator=(const AmgSolver&) = delete;

  // The tangent the next solves use. The hierarchy is rebuilt when the pattern is new (forget()),
  // when there is none, or when the last solve took more than rebuildIterations.
  void setMatrix(const Eigen::SparseMatrix<double>& k);
  // Which displacement component (0 x, 1 y) each unknown is: BoomerAMG coarsens and interpolates
  // each separately (the systems approach for elasticity). Without it, one scalar function; with
  // the components mixed up (an unknown per node where one component is held), AMG is a poor
  // preconditioner (145 GMRES iterations instead of 12 on the DEN coarse elastic tangent).
  void setComponents(std::vector<int> components) { components_ = std::move(components); }
  void forget();  // the next matrix has another pattern
  // K x = b to |b - K x| <= tolerance |b|; false where GMRES did not get there (x is its best).
  bool solve(const Eigen::VectorXd& b, Eigen::VectorXd& x);
  const AmgStatistics& statistics() const { return stats_; }

  double tolerance = 1e-8;  // GMRES's relative residual; the implicit solver sets ImplicitSettings::krylovTolerance
  int maxIterations = 400;
  AmgOptions options;       // read at the next hierarchy's setup
  // Iterations of the last solve.
  int lastIterations() const { return lastIterations_; }

 private:
  struct Hypre;  // hypre's objects (mpm/implicit/amg_solver.cpp)
  std::unique_ptr<Hypre> h_;
  AmgStatistics stats_;
  std::vector<int> components_;
  bool stale_ = true;      // the hierarchy must be rebuilt before the next solve
  int lastIterations_ = 0;
  int freshIterations_ = -1;  // the first solve's iterations on a new hierarchy (-1: none yet)
  // A solve that takes more than this asks for a new hierarchy: twice a fresh one's count plus 10.
  int rebuildIterations() const { return freshIterations_ < 0 ? maxIterations : 2 * freshIterations_ + 10; }
  void setup();
};

}  // namespace ecm::mpm
