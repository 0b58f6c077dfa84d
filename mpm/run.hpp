#pragma once
// A whole run of a scene with its output folder: history.csv (flushed every output step),
// VTU snapshots with a .pvd index, summary.json, a load-displacement PNG, the final particles
// (particles_final.csv: x, y, damage, material, opening) with their damage map PNG, progress on stderr.
// A failure still leaves everything written so far readable, and a summary saying why.
// Both solvers run in the one run loop (mpm/run_loop.hpp). Checkpoints are written as the scene asks and when the run is asked to
// stop; a restart continues the same output folder (history.csv, snapshots) from the checkpoint.
#include "mpm/run_options.hpp"
#include "mpm/scene/scene.hpp"

namespace ecm::mpm {

// Runs the scene to its end time (or its stop_when). Input errors (invalid scene) throw std::invalid_argument and
// an output folder that cannot be written io::OutputError, before anything is written; a
// checkpoint that a restart cannot use throws CheckpointError (mpm/output/checkpoint_codec.hpp), before
// anything is changed. A failure during the run (simulation, or a file that cannot be written)
// is reported in the result (and in summary.json when it can be written) after the outputs have
// been flushed. A completed run removes its checkpoint; a stopped or failed one keeps the last.
RunResult runScene(const Scene& scene, const RunOptions& options);

}  // namespace ecm::mpm
