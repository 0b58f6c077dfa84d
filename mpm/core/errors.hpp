#pragma once
// Loud failures of a run: they name the step, the particle, where it was and why.
#include <cstddef>
#include <stdexcept>
#include <string>

#include "material/update_result.hpp"

namespace ecm::mpm {

enum class FailureKind {
  LeftGrid,         // a particle (or its shape-function support) left the background grid
  NotFinite,        // NaN or infinity in a particle's velocity, position or stress
  MaterialFailure,  // the material update did not converge even after sub-stepping
  EnergyImbalance,  // the damping's work passed the energy put into the run: an unstable step
};

struct SimulationError : std::runtime_error {
  SimulationError(FailureKind k, long stepIndex, std::size_t particleId, const Vec2& x, const std::string& what,
                  UpdateStatus s = UpdateStatus::Converged, double r = 0.0)
      : std::runtime_error(what), kind(k), step(stepIndex), particle(particleId), position(x), status(s), residual(r) {}
  FailureKind kind;
  long step;             // the step during which it happened (1-based)
  std::size_t particle;  // particle id (index in the seeding order)
  Vec2 position;         // mm
  UpdateStatus status;   // MaterialFailure only
  double residual;       // MaterialFailure only (MPa)
};

}  // namespace ecm::mpm
