#pragma once
// The plain state an explicit MPM step works on (the phases of mpm/phases.hpp read and write it;
// mpm/solver.hpp owns one of each). Plain structs, no invariants beyond their sizes.
#include <cstdint>
#include <utility>
#include <vector>

#include "material/material.hpp"
#include "mpm/grid.hpp"
#include "mpm/particles.hpp"
#include "mpm/scatter_order.hpp"
#include "mpm/scene.hpp"

namespace ecm::mpm {

// What the phases read and never change during a run: the scene, its materials, the grid
// geometry in cell units and the number of threads.
struct StepSetup {
  Scene scene;
  std::vector<Material> materials;         // one per scene material, in its order
  Vec2 invCell = Vec2::Ones();             // 1/mm
  Vec2 halfWidth = Vec2::Zero();           // uGIMP half-size of a particle's domain, in cells
  EffectiveSize size;                      // the effective size H of every point (docs/model.md)
  std::vector<std::uint8_t> constrained;   // per node: bit 0 x, bit 1 y is prescribed (no damping there)
  int threads = 1;
};

// The step being taken goes from `time` to `time + dt` and becomes step number `step + 1`.
struct Clock {
  double time = 0.0;  // s
  double dt = 0.0;    // s
  long step = 0;      // steps taken
};

// What the run adds up over its steps (N mm = mJ for the energies).
struct RunTotals {
  double externalWork = 0.0;  // loads, gravity and reactions
  double dissipated = 0.0;    // by the materials (damage)
  double damping = 0.0;       // removed by local and viscous damping
  long substepped = 0;        // material updates that needed sub-stepping
  long released = 0;          // enriched updates that released a snap-back
};

// Energies (N mm = mJ). Kinetic and strain are of the present state; the others accumulate.
struct Energies {
  double kinetic = 0.0;
  double strain = 0.0;        // sum of V sigma.eps / 2 (recoverable for elastic and secant unloading)
  double externalWork = 0.0;  // loads, gravity and reactions
  double dissipated = 0.0;    // by the materials (damage)
  double damping = 0.0;       // removed by local and viscous damping
};

// The runtime state of a node condition: its nodes, the reaction of the step and the
// prescribed displacement so far.
struct ConditionState {
  std::vector<std::int32_t> nodes;
  Vec2 reaction = Vec2::Zero();      // N: sum over the nodes of the constraint forces of the last step
  Vec2 displacement = Vec2::Zero();  // mm: integral of the prescribed velocity (of the field at its origin)
};

struct LoadState {
  std::vector<std::int32_t> members;  // nodes or particles
  Vec2 applied = Vec2::Zero();        // N: the total force applied in the last step
};

// What the fused USL pass carries from one step to the next (fused_transfer.cpp).
struct FusedPass {
  // The grid holds the scatter of the present particles (their mass, momentum and forces, loads
  // not yet added): the next step starts at its grid phase.
  bool gridHoldsState = false;
  std::vector<std::uint32_t> deferred;  // the points left to updateStresses, in index order
  std::vector<std::pair<std::uint32_t, std::uint32_t>> chunkDeferred;  // per chunk of the scatter order: its range in `deferred`
  // Per thread, while the pass runs: its deferred points and its far ones (deferred or not).
  std::vector<std::vector<std::uint32_t>> deferredPerThread, farPerThread;
};

// Everything a step changes.
struct MpmState {
  Particles particles;
  GridFields grid;
  ScatterOrder order;  // the order of the scatter (mpm/scatter_order.hpp)
  std::vector<ConditionState> conditions;  // one per scene condition
  std::vector<LoadState> loads;            // one per scene load
  Clock clock;
  RunTotals totals;
};

}  // namespace ecm::mpm
