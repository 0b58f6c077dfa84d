#pragma once
// The one Newton driver of the implicit steps (docs/implicit.md, "Load steps"): the same
// iteration for every control. Each iteration evaluates the iterate's residual, ends when it is
// converged, or stalled or diverged (mpm/implicit/newton_ends.hpp; then back to the best iterate),
// guards against cycling at the loading/unloading kinks (mpm/implicit/newton_cycle.hpp), and
// solves for the correction on the kept factorisation, by GMRES on the current tangent or on a
// fresh factorisation, bordered by the control's row under indirect control. What differs between
// the controls (the predictor, the residual, how a correction moves the iterate) is their
// StepProblem (mpm/implicit/step_problem.hpp).
#include "mpm/implicit/attempt.hpp"
#include "mpm/implicit/step_problem.hpp"

namespace ecm::mpm {

// Newton on `problem` for the attempt: true when converged; otherwise the attempt says why
// (Attempt::reason), and a stalled one holds its best iterate.
bool solveNewton(StepProblem& problem, const StepContext& context, Attempt& a);

}  // namespace ecm::mpm
