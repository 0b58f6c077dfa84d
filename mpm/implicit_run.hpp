#pragma once
// A whole implicit_static run (docs/implicit.md) with its output folder: history.csv (a row per
// load step: the explicit columns, with kinetic energy and damping 0, then the load factor, the
// step's Newton iterations, halvings, snap-back releases, size and onset overshoot, the internal
// work, the work-based dissipation and whether it was relaxed), VTU snapshots,
// particles_final.csv, summary.json (Newton iterations, factorisations, linear-solve time, both
// dissipations and the energy balance), the plots, and checkpoints and restarts as explicit runs
// have them. runScene() hands implicit scenes here.
#include "mpm/run.hpp"

namespace ecm::mpm {

RunResult runImplicitScene(const Scene& scene, const RunOptions& options);

}  // namespace ecm::mpm
