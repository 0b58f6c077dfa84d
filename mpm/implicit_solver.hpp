#pragma once
// Implicit quasi-static MPM (docs/implicit.md): the scene's time is a pseudo-time that sets the
// loads and the prescribed displacements; each load step solves equilibrium on the grid by
// Newton's method on the nodal displacement increments with the assembled consistent tangent
// (mpm/implicit_system.hpp), a backtracking line search and, when it does not converge, the step
// cut in half. The particles move and their states are committed at the end of a converged step.
//
// Prescribed components over a step [t, t + dt]: Fixed 0; Displacement u(t + dt) - u(t);
// Velocity dt v(t + dt) (a rate in pseudo-time); an affine field dt scale(t + dt) G (x - o).
#include <Eigen/SparseLU>

#include <vector>

#include "mpm/implicit_system.hpp"

namespace ecm::mpm {

struct ImplicitOptions {
  double tolerance = 1e-6;  // |residual| <= tolerance * max(|loads|, |reactions|, |internal forces|)
  int maxIterations = 25;   // Newton iterations per attempt
  int maxCuts = 8;          // halvings of a step before the run fails
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
  bool attempt(double dt, Attempt& a);  // Newton over [time_, time_ + dt]; true when converged
  void commit(const Attempt& a, double dt);

  StepSetup setup_;
  ImplicitOptions options_;
  Particles particles_;
  std::vector<ConditionState> conditions_;
  std::vector<LoadState> loads_;
  RunTotals totals_;
  Eigen::VectorXd previousForce_;  // the internal forces of the last converged step (for the work)
  double time_ = 0.0;
  long steps_ = 0;
};

}  // namespace ecm::mpm
