#pragma once
// A whole implicit_static run (docs/implicit.md) with its output folder: history.csv (a row per
// load step: the explicit columns, with kinetic energy and damping 0, then the load factor, the
// step's Newton iterations, halvings and snap-back releases), particles_final.csv, summary.json
// (Newton iterations, linear-solve time) and the plots. runScene() hands implicit scenes here.
#include "mpm/run.hpp"

namespace ecm::mpm {

RunResult runImplicitScene(const Scene& scene, const RunOptions& options);

}  // namespace ecm::mpm
