#pragma once
// What a caller asks of a run (RunOptions) and what it gets back (RunResult): shared by runScene
// (mpm/run.hpp) and the run loop under it (mpm/run_loop.hpp).
#include <atomic>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>

#include "mpm/core/errors.hpp"

namespace ecm::mpm {

struct RunOptions {
  std::filesystem::path outputDir;
  int threads = 0;        // 0: OpenMP default
  bool snapshots = true;  // VTU particle snapshots
  bool plot = true;       // load-displacement PNG through gnuplot
  bool progress = true;   // progress on stderr
  // Checkpoint and restart.
  bool restart = false;          // continue the run of outputDir from its checkpoint.bin
  std::uint64_t sceneHash = 0;   // FNV-1a 64 of the scene file's bytes (0: a scene built in code);
                                 // a restart refuses a checkpoint written with another one
  long maxSteps = 0;             // > 0: stop with a checkpoint once the step count (from t = 0) reaches it
  const std::atomic<bool>* stop = nullptr;  // once set (a signal handler): stop with a checkpoint after the step
  std::string resumeCommand;     // how to resume, for summary.json (main: "ecm-mpm SCENE --restart DIR")
  // Called after every history row is written (with the time reached, s, and the step count);
  // returning false asks the run to stop with a checkpoint, as `stop` does (the Python module's
  // progress callback).
  std::function<bool(double time, long step)> onRow;
};

struct RunResult {
  bool completed = false;
  bool stopped = false;    // stopped on request (stop flag, maxSteps) after writing a checkpoint
  std::optional<RunFailure> failure;  // why the run failed (a simulation failure or a file that could not be written)
  long steps = 0;          // the step count reached (from t = 0)
  long restartedFrom = -1; // the step of the checkpoint a restart continued from
  std::size_t particles = 0;
  double peakLoad = 0.0;   // N: the largest reaction of a driven condition (or applied load)
  bool endedByStopWhen = false;  // completed at the scene's stop_when, before end_time
  double stopLoad = 0.0;         // N: the watched reaction at that row
  double wallTime = 0.0;   // s, of this run (a restart counts from its own start)
  long checkpoints = 0;    // written by this run
  std::filesystem::path checkpoint;  // the checkpoint left in the folder (empty: none)

  // The failure's message ("" when the run did not fail): for people, never to be parsed.
  std::string message() const { return failure ? failure->message : std::string(); }
};

}  // namespace ecm::mpm
