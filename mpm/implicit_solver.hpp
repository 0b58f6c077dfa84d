#pragma once
// Implicit quasi-static MPM (docs/implicit.md): the scene's time is a pseudo-time that sets the
// loads and the prescribed displacements; each load step solves equilibrium on the grid by
// Newton's method on the nodal displacement increments with the assembled consistent tangent
// (mpm/implicit_system.hpp), a backtracking line search and, when it does not converge, the step
// cut in half. The particles move and their states are committed at the end of a converged step.
//
// Prescribed components over a step [t, t + dt]: Fixed 0; Displacement u(t + dt) - u(t);
// Velocity dt v(t + dt) (a rate in pseudo-time); an affine field dt scale(t + dt) G (x - o).

#include <vector>

#include "mpm/implicit_system.hpp"
#include "mpm/linear_solver.hpp"

namespace ecm::mpm {

struct ImplicitOptions {
  double tolerance = 1e-6;  // |residual| <= tolerance * max(|loads|, |reactions|, |internal forces|)
  int maxIterations = 25;   // Newton iterations per attempt
  int maxCuts = 8;          // halvings of a step before the run fails
  LinearSolverKind linearSolver = available(LinearSolverKind::Umfpack) ? LinearSolverKind::Umfpack : LinearSolverKind::SparseLU;
};

// Indirect displacement control (docs/implicit.md): the driven conditions' prescribed components
// move by lambda times `reference` (mm per unit load factor), lambda an unknown of each step, and
// the step is set by the growth of a combination of node displacements instead:
// tau = sum_k c_k u_k over node components k = 2 n + d (an opening across a crack, a crack mouth).
// The grid is reset every step, so the control is on the step's increments: d tau = sum c_k du_k.
struct IndirectControl {
  std::vector<std::size_t> driven;                     // indices of scene conditions
  Vec2 reference = Vec2(0.0, 1.0);                     // mm per unit load factor, on their non-fixed components
  std::vector<std::pair<std::int32_t, double>> terms;  // (node component, coefficient)
};

struct ImplicitStepReport {
  int iterations = 0;       // Newton iterations of the converged attempt (all attempts in `total`)
  int totalIterations = 0;
  int cuts = 0;             // halvings needed
  double residual = 0.0;    // relative, at convergence
  long released = 0;        // snap-backs released at the material level in the step
  double linearSolveSeconds = 0.0;
};

class ImplicitSolver {
 public:
  ImplicitSolver(Scene scene, int threads = 1, ImplicitOptions options = {});

  // One load step from time() to time() + dt, in halves when needed. Throws SimulationError
  // (with the step, the iteration, the residual and the worst particle) when even the smallest
  // piece fails; the committed state is then the last converged one.
  ImplicitStepReport step(double dt);
  // One step of indirect control: the combination grows by dTau (mm), lambda follows; halved as
  // step() halves. The pseudo-time does not move.
  ImplicitStepReport step(const IndirectControl& control, double dTau);
  double loadFactor() const { return lambda_; }

  double time() const { return time_; }
  long steps() const { return steps_; }
  const Particles& particles() const { return particles_; }
  const std::vector<ConditionState>& conditions() const { return conditions_; }
  const StepSetup& setup() const { return setup_; }
  Energies energies() const;
  // The particles' displacements from their seeds (mm).
  Vec2 displacement(std::size_t i) const { return particles_.displacement(i); }

 private:
  struct Attempt;
  // The step's prescribed components, geometry and loads (false: a particle left the grid).
  bool prepare(double dt, const IndirectControl* control, Attempt& a);
  bool attempt(double dt, Attempt& a);  // Newton over [time_, time_ + dt]; true when converged
  bool attemptIndirect(const IndirectControl& control, double dTau, Attempt& a);
  template <class Try>
  ImplicitStepReport halving(double size, Try&& tryPiece);  // the step in pieces, halved on failure
  void commit(const Attempt& a, double dt);

  StepSetup setup_;
  ImplicitOptions options_;
  Particles particles_;
  std::vector<ConditionState> conditions_;
  std::vector<LoadState> loads_;
  RunTotals totals_;
  Eigen::VectorXd previousForce_;  // the internal forces of the last converged step (for the work)
  double time_ = 0.0;
  double lambda_ = 0.0;  // the load factor of indirect control
  long steps_ = 0;
};

}  // namespace ecm::mpm
