#pragma once
// A piece's equilibrium problem as the one Newton driver (mpm/implicit/newton.hpp) sees it: the
// predictor, the residual (with, under indirect control, the border row of the load factor), and
// how a correction moves the iterate. Two implementations: displacement control
// (mpm/implicit/displacement_control.hpp) and indirect control (mpm/implicit/indirect_control.hpp).
#include <Eigen/Core>
#include <optional>

#include "mpm/implicit/attempt.hpp"
#include "mpm/implicit/kept_factorization.hpp"
#include "mpm/implicit/newton_cycle.hpp"

namespace ecm::mpm {

// What a step's Newton works with besides its attempt: the committed state, the step's geometry,
// the settings and the kept factorisation (`factorKey` names the unknowns of this step).
struct StepContext {
  const StepSetup& setup;
  const Particles& particles;
  const StepGeometry& geometry;
  const ImplicitSettings& settings;
  KeptFactorization& factors;
  long factorKey = 0;
};

// The border of indirect control's system, from the iterate: K's product with the driven
// components' reference on the unknowns (ku), the control's coefficients on the unknowns (c) and
// through the driven components (cPrescribed), and the control's residual g = d tau - c . du.
struct ControlRow {
  Eigen::VectorXd ku;
  const Eigen::VectorXd* c = nullptr;
  double cPrescribed = 0.0;
  double g = 0.0;
};

// The residual of an iterate.
struct Residual {
  Eigen::VectorXd r;       // f_ext - f_int on the (reduced) unknowns (N)
  double relative = 0.0;   // |r| / max(|f_ext|, |f_int|)
  bool meetsControl = true;  // the iterate meets the control (always, under displacement control)
  bool mayConverge = true;   // the iterate may end Newton when its residual is small enough
  std::optional<ControlRow> border;  // indirect control
};

// Newton's correction on the (reduced) unknowns, and of the load factor under indirect control.
struct Correction {
  Eigen::VectorXd step;
  double loadFactor = 0.0;
};

// An iterate, as Newton's history keeps its best one: du (under indirect control without the load
// factor's share) and the load factor's increment.
struct Iterate {
  Eigen::VectorXd du;
  double loadFactor = 0.0;
};

class StepProblem {
 public:
  virtual ~StepProblem() = default;
  // The first iterate and its trial (attempt.trial). False: the piece failed before Newton (the
  // attempt says why).
  virtual bool start() = 0;
  // The residual of the current iterate (Newton's iteration `iteration`).
  virtual Residual residual(int iteration) = 0;
  virtual Iterate iterate() const = 0;
  // Moves the iterate by Newton's correction and evaluates its trial (the secant tangents the
  // guard asks for). Where no step length gives a trial whose material updates all converge,
  // attempt.trial holds the full correction's failed trial.
  virtual void move(const Correction& d, const Residual& r, const CycleGuard& cycle) = 0;
  // Newton gives up: back to the best iterate (its trial evaluated again) when there is one,
  // otherwise the last.
  virtual void backTo(const Iterate* best, const CycleGuard& cycle) = 0;
  // The iterate is the attempt's result (converged or given up): what the commit needs of it.
  virtual void finish() = 0;
};

}  // namespace ecm::mpm
