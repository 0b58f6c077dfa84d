#pragma once
// The plain state an explicit MPM step works on (the phases of mpm/explicit/phases.hpp read and
// write it; mpm/explicit/explicit_solver.hpp owns one of each). Plain structs, no invariants beyond their sizes.
#include <cstdint>
#include <utility>
#include <vector>

#include "mpm/core/grid.hpp"
#include "mpm/core/particles.hpp"
#include "mpm/explicit/scatter_order.hpp"
#include "mpm/setup/crack_paths.hpp"
#include "mpm/setup/step_setup.hpp"

namespace ecm::mpm {

// The step being taken goes from `time` to `time + dt` and becomes step number `step + 1`.
struct Clock {
  double time = 0.0;  // s
  double dt = 0.0;    // s
  long step = 0;      // steps taken
};

// What the fused USL pass carries from one step to the next (fused_transfer.cpp).
struct FusedPass {
  // The grid holds the scatter of the present particles (their mass, momentum and forces, loads
  // not yet added): the next step starts at its grid phase.
  bool gridHoldsState = false;
  // The mass and volume each material's points share (sharedMassAndVolume; empty: they differ,
  // the pass reads the per-point arrays), found again whenever the grid is rebuilt.
  std::vector<SharedMassVolume> shared;
  std::vector<std::uint32_t> deferred;  // the points left to updateStresses, in index order
  std::vector<std::pair<std::uint32_t, std::uint32_t>> chunkDeferred;  // per chunk of the scatter order: its range in `deferred`
  // Per thread, while the pass runs: its deferred points and its far ones (deferred or not).
  std::vector<std::vector<std::uint32_t>> deferredPerThread, farPerThread;
};

// Everything a step changes.
struct MpmState {
  Particles particles;
  GridFields grid;
  ScatterOrder order;  // the order of the scatter (mpm/explicit/scatter_order.hpp)
  std::vector<ConditionState> conditions;  // one per scene condition
  std::vector<LoadState> loads;            // one per scene load
  std::vector<PlatenState> platens;        // one per scene platen
  Clock clock;
  RunTotals totals;
  CrackPaths crackPaths;  // where enriched points may open bands (docs/model.md, "Crack paths")
};

}  // namespace ecm::mpm
