#pragma once
// The one run loop of both solvers (mpm/run.hpp's runScene), in the manner of cb-geo's MPMBase:
// the loop owns the stop requests (signal, --max-steps, the row callback), the checkpoint
// schedule, the output folder and what happens when a file cannot be written, the history rows'
// timing, the VTU and particle snapshots, the peak and the scene's stop_when, the progress bar,
// the summary's common keys and the plots. A solver supplies a Stepper: its step, its history
// row, its checkpoint payload and its own summary keys. mpm/explicit_run.cpp and
// mpm/implicit_run.cpp are the two.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "mpm/output/checkpoint_codec.hpp"
#include "mpm/run_options.hpp"
#include "mpm/scene/scene.hpp"
#include "mpm/setup/crack_paths.hpp"
#include "mpm/setup/step_setup.hpp"

namespace ecm::mpm {

class Stepper {
 public:
  virtual ~Stepper() = default;

  // --- what the loop watches ---
  virtual const Particles& particles() const = 0;
  // The same for readers of positions and displacements every step (the gauges), which need no
  // stresses: the explicit solver stores its intact points' stresses only for particles().
  virtual const Particles& kinematics() const { return particles(); }
  virtual const std::vector<ConditionState>& conditions() const = 0;
  virtual const std::vector<PlatenState>& platens() const = 0;
  virtual const CrackPaths& crackPaths() const = 0;  // (written as crack_paths.csv when tracked)
  virtual std::vector<Vec2> appliedLoads() const = 0;  // N, per scene load, now
  virtual long steps() const = 0;
  virtual double time() const = 0;  // s (implicit: pseudo-time), for the row callback
  // Where the run is on its way to its end, in the unit of the progress bar and of the snapshot
  // times: the time (explicit), the pseudo-time and then the opening (implicit).
  virtual double progress() const = 0;
  virtual double progressEnd() const = 0;
  virtual bool reachedEnd() const = 0;           // progress() at progressEnd(), round-off aside
  virtual double progressTolerance() const = 0;  // (half a step) for the particle snapshots' times
  virtual std::string progressLabel() const = 0;

  // --- the loop's calls ---
  virtual void advance() = 0;           // one step; throws SimulationError
  virtual bool rowDue() const = 0;      // after a step: is a history row due (besides at the end)?
  virtual void rowWritten() = 0;        // the row was written
  virtual std::vector<std::string> historyColumns() const = 0;
  virtual std::vector<double> historyRow() const = 0;
  // At each history row, before it is written: throws SimulationError where the run's energy
  // account says a step went unstable (explicit: mpm/explicit/energy_check.hpp).
  virtual void checkEnergy() const {}
  // A VTU snapshot with the row of index `row` (besides the end); snapshotTaken: one was written.
  virtual bool snapshotDue(std::size_t row) const = 0;
  virtual void snapshotTaken() {}
  // How a failure leaves the state: the last consistent one (implicit: a checkpoint of it is
  // written and a snapshot taken), or the failed step's (explicit: its row and snapshot are
  // written, to look at what went wrong). A stopped run's snapshot where it stopped: implicit.
  virtual bool failureKeepsConsistentState() const = 0;

  // --- checkpoints: the solver's state and its own bookkeeping, with the loop's RunBook ---
  virtual RunBook& book() = 0;
  virtual void writeCheckpoint(const std::filesystem::path& path, std::uint64_t sceneHash) = 0;
  virtual void readCheckpoint(const std::filesystem::path& path, std::uint64_t sceneHash) = 0;  // throws CheckpointError

  // --- the solver's keys of summary.json (the loop adds the common ones) ---
  virtual nlohmann::json summary(const RunResult& result) const = 0;
};

// Runs `stepper` (built from `scene`) to its end with the outputs of `options`: as runScene.
RunResult runLoop(const Scene& scene, const RunOptions& options, Stepper& stepper);

}  // namespace ecm::mpm
