#pragma once
// A whole run of a scene with its output folder: history.csv (flushed every output step),
// VTU snapshots with a .pvd index, summary.json, a load-displacement PNG, the final particles
// (particles_final.csv: x, y, damage, material, opening) with their damage map PNG, progress on stderr.
// A failure still leaves everything written so far readable, and a summary saying why.
#include <filesystem>
#include <string>

#include "mpm/scene.hpp"

namespace ecm::mpm {

struct RunOptions {
  std::filesystem::path outputDir;
  int threads = 0;        // 0: OpenMP default
  bool snapshots = true;  // VTU particle snapshots
  bool plot = true;       // load-displacement PNG through gnuplot
  bool progress = true;   // progress on stderr
};

struct RunResult {
  bool completed = false;
  std::string error;       // why the run stopped early
  long steps = 0;
  std::size_t particles = 0;
  double peakLoad = 0.0;   // N: the largest reaction of a driven condition (or applied load)
  double wallTime = 0.0;   // s
};

// Runs the scene to its end time. Input errors (invalid scene) throw std::invalid_argument
// before anything is written; a failure during the run is reported in the result (and in
// summary.json) after the outputs have been flushed.
RunResult runScene(const Scene& scene, const RunOptions& options);

// The columns of history.csv for a scene.
std::vector<std::string> historyColumns(const Scene& scene);

}  // namespace ecm::mpm
