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

#include "mpm/explicit/explicit_solver.hpp"

namespace ecm::mpm {

// The share of the energy put in that the damping's work may reach, either way: all of it.
inline constexpr double kDampingWorkLimit = 1.0;

// Whether the damping's work (N mm) has left [-limit, limit] times what was put in (the external
// work and `initial`, the kinetic and strain energy at step 0). Pure; the run's totals alone, no
// pass over the particles.
inline bool dampingOutrunsInput(const RunTotals& t, double initial) {
  return std::abs(t.damping) > kDampingWorkLimit * std::max(t.externalWork + initial, 0.0) && t.damping != 0.0;
}

// Throws SimulationError (DampingWork) where dampingOutrunsInput, naming the step, the time,
// both energies and the fastest particle.
void checkDampingWork(const ExplicitSolver& solver, double initial);

}  // namespace ecm::mpm
