#pragma once
// The bound on the damping's work that both solvers check (docs/model.md, "The damping's work"):
// the damping (explicit: local and viscous damping; implicit: a stabilised step's dashpots,
// docs/implicit.md) can take out of a run no more energy than was put into it, the external work
// and the energy the particles start with, and it puts none in. Past either bound it is no longer
// damping: a step went unstable.
#include <algorithm>
#include <cmath>

#include "mpm/setup/step_setup.hpp"

namespace ecm::mpm {

// The share of the energy put in that the damping's work may reach, either way: all of it.
inline constexpr double kDampingWorkLimit = 1.0;

// Whether the damping's work (N mm) has left [-limit, limit] times what was put in (the external
// work and `initial`, the kinetic and strain energy at step 0). Pure; the run's totals alone, no
// pass over the particles.
inline bool dampingOutrunsInput(const RunTotals& t, double initial) {
  return std::abs(t.damping) > kDampingWorkLimit * std::max(t.externalWork + initial, 0.0) && t.damping != 0.0;
}

}  // namespace ecm::mpm
