#pragma once
// The explicit run's energy check (docs/model.md, "The damping's work"): the damping can take
// out of the run no more energy than was put into it, the external work and the energy the
// particles start with, and it puts none in. Past either bound the damping's work is no longer
// damping: a step went unstable (a node whose velocity flips within a step while the damping,
// signed by the old velocity, pushes it on, for one), and the energies run away. The run stops at
// that row, loudly, with the fastest particle as where.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <optional>
#include <string>

#include "mpm/setup/damping_limit.hpp"  // kDampingWorkLimit, dampingOutrunsInput
#include "mpm/explicit/explicit_solver.hpp"

namespace ecm::mpm {

// Throws SimulationError (DampingWork) where dampingOutrunsInput, naming the step, the time,
// both energies and the fastest particle.
void checkDampingWork(const ExplicitSolver& solver, double initial);

}  // namespace ecm::mpm
