#pragma once
// The explicit solver's part of a run (mpm/run_loop.hpp): its Stepper.
#include <memory>

#include "mpm/run_loop.hpp"

namespace ecm::mpm {

// Builds the solver (seeding the scene; throws on a scene it cannot seed, before any output).
std::unique_ptr<Stepper> explicitStepper(const Scene& scene, const RunOptions& options);

}  // namespace ecm::mpm
