#pragma once
// Displacement control's Newton problem for a piece of pseudo-time (docs/implicit.md, "Load
// steps"): the prescribed components move by their histories' increments; the predictor is the
// step linearised at its start, loaded by them; a correction is taken with a backtracking line
// search on |r|.
#include "mpm/implicit/step_problem.hpp"

namespace ecm::mpm {

class DisplacementControl final : public StepProblem {
 public:
  DisplacementControl(const StepContext& context, Attempt& a) : context_(context), a_(a) {}

  bool start() override;
  Residual residual(int iteration) override;
  Iterate iterate() const override { return {a_.du, 0.0}; }
  void move(const Correction& d, const Residual& r, const CycleGuard& cycle) override;
  void backTo(const Iterate* best, const CycleGuard& cycle) override;
  void finish() override {}

 private:
  // f_ext - f_int of a trial on the unknowns, and its norm relative to the forces.
  Eigen::VectorXd residualOf(const Trial& t, double& relative) const;
  void evaluate(const Eigen::VectorXd& du, Trial& t, const CycleGuard* cycle) const;

  const StepContext& context_;
  Attempt& a_;
};

}  // namespace ecm::mpm
