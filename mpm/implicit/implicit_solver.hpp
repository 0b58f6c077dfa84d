#pragma once
// Implicit quasi-static MPM (docs/implicit.md): the scene's time is a pseudo-time that sets the
// loads and the prescribed displacements; each load step solves equilibrium on the grid by
// Newton's method on the nodal displacement increments with the assembled consistent tangent
// (mpm/implicit/implicit_system.hpp) and, when it does not converge, the step cut in half. The
// particles move and their states are committed at the end of a converged step.
// Where each part is: the step's prescribed components, platens, ties and loads in
// step_preparation.cpp; Newton in newton.cpp over the control's problem (displacement_control.cpp,
// indirect_control.cpp); the adaptive pieces and halvings in load_stepping.cpp; the commit (the
// particles moved, reactions, works) in step_commit.cpp.
//
// Prescribed components over a step [t, t + dt]: Fixed 0; Displacement u(t + dt) - u(t);
// Velocity dt v(t + dt) (a rate in pseudo-time); an affine field dt scale(t + dt) G (x - o).

#include <array>
#include <vector>

#include "mpm/implicit/attempt.hpp"
#include "mpm/implicit/implicit_system.hpp"
#include "mpm/implicit/indirect_control.hpp"
#include "mpm/implicit/kept_factorization.hpp"
#include "mpm/implicit/platen_and_tie_unknowns.hpp"

namespace ecm::mpm {

class ImplicitSolver {
 public:
  // The solver's settings are the scene's `solver.implicit` (their defaults where it has none).
  explicit ImplicitSolver(Scene scene, int threads = 1);

  // One load step from time() to time() + dt, in halves when needed. Throws SimulationError
  // (with the step, the iteration, the residual and the worst particle) when even the smallest
  // piece fails; the committed state is then the last converged one.
  ImplicitStepReport step(double dt);
  // One step of indirect control: the combination grows by dTau (mm), lambda follows; halved as
  // step() halves. The pseudo-time does not move.
  ImplicitStepReport step(const IndirectControl& control, double dTau);
  // One converged load step of at most `largest` and `remaining` (its size in the report): the
  // adaptive step of a run. The piece follows the Newton iterations and the onset overshoot of the
  // last one, not below largest / 2^maxHalvings. A piece whose Newton does not converge is tried
  // again factorising at every iteration, then halved up to maxHalvings times; the last try has 4
  // times the iterations. A material snap-back follows the scene's snap_back: release (the band
  // fails onto its stable branch where the converged state asks for it, counted, no halving) or
  // stop (one halving; if it persists, a SimulationError of kind MaterialFailure, status SnapBack,
  // naming the point).
  // Throws SimulationError as step() does.
  ImplicitStepReport advance(double largest, double remaining);
  ImplicitStepReport advance(const IndirectControl& control, double largest, double remaining);
  double loadFactor() const { return lambda_; }
  const LinearSolver& linearSolver() const { return factors_.linearSolver(); }
  // The tangent over the unknowns of a step of dt from here, at du = 0 (for benchmarks of the
  // linear solvers); empty if a particle left the grid. components: which displacement
  // component (0 x, 1 y) each unknown is, as AmgSolver::setComponents takes it.
  Eigen::SparseMatrix<double> tangentAtStart(double dt, std::vector<int>* components = nullptr);

  // What a checkpoint stores besides the particles (mpm/implicit/implicit_checkpoint.hpp): with it and the
  // particles, a solver of the same scene continues bitwise as the one that was saved.
  struct SavedState {
    double time = 0.0, loadFactor = 0.0, nextPiece = 0.0, nextOpening = 0.0;
    long steps = 0;
    double externalWork = 0.0, internalWork = 0.0, dissipated = 0.0;
    double dashpotWork = 0.0;  // stabilised steps' (docs/implicit.md, "Stabilised steps")
    long released = 0;
    std::vector<Vec2> reactions, conditionDisplacements;  // per condition
    // The last step's geometry (its stencils' first nodes, its prescribed components) and the
    // tangent factorised on it (empty when the factorisation is of another pattern, or none).
    std::vector<std::int32_t> stencilBases;
    std::vector<std::uint8_t> prescribed;
    Eigen::SparseMatrix<double> factored;
    // When it is of reduced unknowns (platens, node ties: mpm/implicit/platen_and_tie_unknowns.hpp), the
    // reduction's layout it was made for.
    bool factoredReduced = false;
    std::vector<std::array<bool, 3>> platenLayout;
    std::vector<NodeTie> tieLayout;
    // Indirect control: the last step's increments (empty, 0: none).
    Eigen::VectorXd lastIncrement;
    double lastLoadFactorIncrement = 0.0, lastOpening = 0.0;
  };
  SavedState saved() const;
  // Throws std::invalid_argument when the state does not fit this solver's scene.
  void restore(const SavedState& s);
  Particles& editParticles() { return particles_; }
  const CrackPaths& crackPaths() const { return crackPaths_; }
  CrackPaths& editCrackPaths() { return crackPaths_; }

  double time() const { return time_; }
  long steps() const { return steps_; }
  const Particles& particles() const { return particles_; }
  const std::vector<ConditionState>& conditions() const { return conditions_; }
  const std::vector<PlatenState>& platens() const { return platens_; }
  std::vector<PlatenState>& editPlatens() { return platens_; }
  const StepSetup& setup() const { return setup_; }
  Energies energies() const;
  // The internal work (N mm): sum_p V int sigma : d eps, trapezoidal per step. External work minus
  // it is the work of the residual forces; internal work minus the strain energy is the work-based
  // dissipation, which on shear paths differs from the model's f int Y dD (docs/implicit.md).
  double internalWork() const { return internalWork_; }
  // The particles' displacements from their seeds (mm).
  Vec2 displacement(std::size_t i) const { return particles_.displacement(i); }

 private:
  // The step's prescribed components, geometry and loads (false: a particle left the grid).
  bool prepare(double dt, const IndirectControl* control, Attempt& a);
  // Newton over the piece (of pseudo-time dt, or of opening under `control`); true when converged.
  bool solvePiece(const IndirectControl* control, double piece, Attempt& a);
  // A piece of displacement control that Newton cannot solve, stabilised by dashpots at its cracked
  // points and solved again with them weakened to 0 (docs/implicit.md, "Stabilised steps"): true
  // with `a` the attempt of the smallest alpha that converged.
  bool solveStabilized(double piece, Attempt& a);
  static constexpr int kMaxProximalSteps = 400;
  static constexpr double kLargestStabilization = 1.0;  // alpha
  static constexpr double kFinishFromRelative = 100.0;  // Newton finishes a proximal solution within 100 tolerances
  ImplicitStepReport advance(const IndirectControl* control, double largest, double remaining);
  ImplicitStepReport stepInPieces(const IndirectControl* control, double size);
  // Returns the energy a stabilised step's dashpots took (0 for any other step).
  double commit(const Attempt& a, double dt);
  // Grows the crack paths from a converged trial; how many of its held points are now on a path.
  std::size_t growCrackPaths(const Trial& t);
  static constexpr int kMaxPathRedos = 50;  // tries of one piece with grown paths
  // Throws SimulationError when the external and internal works part by more than
  // kBalanceTolerance of the work (checked after every step).
  void checkBalance() const;
  static constexpr double kBalanceTolerance = 1e-2;

  StepSetup setup_;
  ImplicitSettings settings_;
  Particles particles_;
  std::vector<ConditionState> conditions_;
  std::vector<LoadState> loads_;
  std::vector<PlatenState> platens_;
  RunTotals totals_;
  KeptFactorization factors_;
  // The unknowns a factorisation is of: the geometry's pattern, which platen degrees of freedom
  // are prescribed (a platen free until some time changes them without a new pattern), and which
  // nodes are tied (mpm/implicit/node_ties.hpp): a change of either is a new reduction layout.
  std::vector<std::array<bool, 3>> platenLayout_;
  std::vector<NodeTie> tieLayout_;
  long reductionLayouts_ = 0;
  long factorKey() const { return geometry_.patternBuilds + (reductionLayouts_ << 32); }
  CrackPaths crackPaths_;  // where enriched points may open bands (docs/model.md, "Crack paths")
  StepGeometry geometry_;  // of the committed state after `geometryStep_` steps (-1: none)
  long geometryStep_ = -1;
  double internalWork_ = 0.0;  // sum over steps and particles of V (sigma_n + sigma_n+1)/2 : d eps (N mm)
  double time_ = 0.0;
  double lambda_ = 0.0;  // the load factor of indirect control
  double nextPiece_ = 0.0;    // the adaptive step of pseudo-time (0: the largest)
  double nextOpening_ = 0.0;  // the adaptive step of indirect control's opening (mm; 0: the largest)
  LastIncrement lastIncrement_;  // indirect control's last step (its Newton starts the next)
  long steps_ = 0;
};

}  // namespace ecm::mpm
