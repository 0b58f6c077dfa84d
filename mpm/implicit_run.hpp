#pragma once
// The implicit_static solver's part of a run (mpm/run_loop.hpp; docs/implicit.md): its Stepper.
// history.csv has a row per load step: the explicit columns (kinetic energy and damping 0), then
// the load factor, the step's Newton iterations, halvings, snap-back releases, size and onset
// overshoot, the internal work, the work-based dissipation and whether it was relaxed;
// summary.json adds Newton iterations, factorisations, linear-solve time, both dissipations and
// the energy balance.
#include <memory>

#include "mpm/run_loop.hpp"

namespace ecm::mpm {

std::unique_ptr<Stepper> implicitStepper(const Scene& scene, const RunOptions& options);

}  // namespace ecm::mpm
