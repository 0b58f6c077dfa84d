// The implicit_static run loop and its outputs (mpm/implicit_run.hpp).
#include "mpm/implicit_run.hpp"

#include <chrono>
#include <cmath>
#include <memory>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "io/csv_writer.hpp"
#include "io/json_summary.hpp"
#include "io/output_dir.hpp"
#include "io/output_error.hpp"
#include "io/progress.hpp"
#include "mpm/errors.hpp"
#include "mpm/implicit_checkpoint.hpp"
#include "mpm/implicit_solver.hpp"
#include "mpm/stop_when.hpp"
#include "mpm/vtu_writer.hpp"

namespace ecm::mpm {

namespace {

using WallClock = std::chrono::steady_clock;

double secondsSince(WallClock::time_point t) { return std::chrono::duration<double>(WallClock::now() - t).count(); }

// The scene's indirect control in node components: each term on the grid node nearest its point.
IndirectControl indirectControl(const Scene& scene) {
  const ImplicitSettings::Indirect& in = *scene.solver.implicit->indirect;
  IndirectControl c;
  for (const std::string& name : in.driven) c.driven.push_back(*findCondition(scene.conditions, name));
  c.reference = in.reference;
  const Grid& g = scene.grid;
  for (const ControlTerm& t : in.terms) {
    const Vec2 local = (t.at - g.origin).cwiseQuotient(g.cellSize);
    const int i = static_cast<int>(std::lround(local[0])), j = static_cast<int>(std::lround(local[1]));
    c.terms.push_back({2 * g.node(i, j) + t.component, t.coefficient});
  }
  return c;
}

ImplicitOptions solverOptions(const ImplicitSettings& s) {
  ImplicitOptions o;
  o.tolerance = s.tolerance;
  o.maxIterations = s.maxIterations;
  o.maxCuts = s.maxHalvings;
  o.onsetOvershoot = s.onsetOvershoot;
  o.acceptTolerance = s.acceptTolerance;
  o.linearSolver = s.umfpack ? LinearSolverKind::Umfpack : LinearSolverKind::SparseLU;
  return o;
}

std::vector<std::string> implicitColumns(const Scene& scene) {
  std::vector<std::string> columns = historyColumns(scene);
  for (const char* c : {"load_factor", "newton_iterations", "halvings", "snapback_releases", "load_step", "onset_overshoot",
                        "internal_work_Nmm", "work_dissipated_Nmm", "relaxed"})
    columns.emplace_back(c);
  return columns;
}

// The run in parts, as the explicit Run (mpm/run.cpp):
//   loop        one adaptive load step at a time (ImplicitSolver::advance) to the end of the
//               pseudo-time, or of the opening under indirect control
//   output      a history row per load step; VTU snapshots at every snapshot_every-th multiple
//               of output_interval (pseudo-time, or mm of opening) and at the start and end
//   checkpoint  on a stop request, after a failure, and as the scene's checkpoint key asks
class ImplicitRun {
 public:
  ImplicitRun(const Scene& scene, const RunOptions& options)
      : scene_(scene), settings_(*scene.solver.implicit), options_(options), start_(WallClock::now()),
        solver_(scene, options.threads, solverOptions(settings_)), checkpointFile_(checkpointPath(options.outputDir)),
        lastCheckpoint_(start_) {
    result_.particles = solver_.particles().size();
    for (const NodeCondition& c : scene.conditions) anyDriven_ = anyDriven_ || isDriven(c);
    if (settings_.indirect) control_ = indirectControl(scene);
    from_ = settings_.indirect ? settings_.indirect->from : scene.endTime;
    total_ = settings_.indirect ? from_ + settings_.indirect->until : scene.endTime;
    if (scene.stopWhen) {
      watched_ = findCondition(scene.conditions, scene.stopWhen->condition).value();  // validated
      watchedComponent_ = drivenComponent(scene.conditions.at(watched_));
    }
    if (options.restart) readRestart();  // before anything in the folder is touched
    io::prepareOutputDir(options.outputDir);
    openOutputs();
  }

  RunResult execute() {
    try {
      if (!options_.restart) output();
      stepLoop();
      result_.completed = !result_.stopped;
    } catch (const SimulationError& e) {
      result_.error = e.what();
      try {
        checkpoint();  // the last converged state
      } catch (const io::OutputError& o) {
        outputFailure(o);
      }
    } catch (const io::OutputError& e) {
      result_.error = std::string(e.what()) + " (at step " + std::to_string(solver_.steps()) + ")";
      outputFailed_ = true;
    }
    if (progress_) progress_->finish();
    try {
      if (!outputFailed_) {
        if (snapshots_ && !result_.completed) snapshots_->add(solver_.particles(), book_.progress);  // where it stopped
        history_->close();
        writeParticles(solver_.particles(), options_.outputDir / "particles_final.csv");
      }
    } catch (const io::OutputError& o) {
      outputFailure(o);
    }
    result_.steps = solver_.steps();
    result_.wallTime = secondsSince(start_);
    std::error_code ec;
    if (result_.completed) std::filesystem::remove(checkpointFile_, ec);  // it describes an unfinished run
    if (std::filesystem::exists(checkpointFile_, ec)) result_.checkpoint = checkpointFile_;
    try {
      io::writeJsonSummary(summary(), options_.outputDir / "summary.json");
    } catch (const io::OutputError& o) {
      outputFailure(o);
    }
    if (!outputFailed_ && options_.plot && !result_.stopped) {
      plotLoadDisplacement(scene_, options_.outputDir);
      plotDamage(scene_, solver_.particles().size(), options_.outputDir);
    }
    return result_;
  }

 private:
  // --- the loop ---
  void stepLoop() {
    while (book_.progress < total_ * (1.0 - 1e-12)) {
      if (stopRequested()) {
        checkpoint();
        result_.stopped = true;
        result_.error = "stopped on request at step " + std::to_string(solver_.steps()) + " (checkpoint written)";
        break;
      }
      // Load steps of pseudo-time to `from_` (the end time without indirect control), then the
      // indirect control's steps of opening: the progress is the pseudo-time, then `from_` plus
      // the opening (mm).
      const bool controlled = settings_.indirect && book_.progress >= from_ * (1.0 - 1e-12);
      const ImplicitStepReport r = controlled ? solver_.advance(control_, settings_.indirect->step, total_ - book_.progress)
                                              : solver_.advance(settings_.loadStep, from_ - book_.progress);
      book_.progress += r.size;
      if (!controlled && std::abs(book_.progress - from_) <= 1e-12 * from_) book_.progress = from_;
      book_.iterations += r.totalIterations, book_.halvings += r.cuts, book_.released += r.released;
      book_.factorizations += r.factorizations;
      book_.relaxed += r.relaxed;
      book_.mostIterations = std::max(book_.mostIterations, static_cast<long>(r.totalIterations));
      book_.linearSolveSeconds += r.linearSolveSeconds;
      trackPeak();
      row(r);
      snapshotIfDue();
      if (options_.onRow && !options_.onRow(solver_.time(), solver_.steps())) rowObserverAsksStop_ = true;
      if (scene_.stopWhen && watch_.observe(*scene_.stopWhen, book_.progress,
                                            solver_.conditions()[watched_].reaction[watchedComponent_])) {
        result_.endedByStopWhen = true;  // the load has fallen below the scene's fraction of its peak
        result_.stopLoad = solver_.conditions()[watched_].reaction[watchedComponent_];
        if (snapshots_) snapshots_->add(solver_.particles(), book_.progress);
        break;
      }
      if (progress_) progress_->update(book_.progress);
      if (book_.progress < total_ * (1.0 - 1e-12) && checkpointDue()) checkpoint();
    }
  }
  bool stopRequested() const {
    return rowObserverAsksStop_ || (options_.stop && options_.stop->load(std::memory_order_relaxed)) ||
           (options_.maxSteps > 0 && solver_.steps() >= options_.maxSteps);
  }
  // The peak of the driven conditions' reactions (all conditions' if none is driven) and loads, as
  // explicit runs report it.
  void trackPeak() {
    for (std::size_t i = 0; i < scene_.conditions.size(); ++i)
      if (isDriven(scene_.conditions[i]) || !anyDriven_)
        book_.peakLoad = std::max(book_.peakLoad, solver_.conditions()[i].reaction.norm());
    for (const Load& l : scene_.loads) book_.peakLoad = std::max(book_.peakLoad, (l.force * l.history(solver_.time())).norm());
  }

  // --- output ---
  void openOutputs() {
    const std::filesystem::path& dir = options_.outputDir;
    history_ = openHistory(dir, implicitColumns(scene_), checkpointFile_, options_.restart ? &book_.history : nullptr);
    if (options_.snapshots) {
      snapshots_ = std::make_unique<VtuSeries>(dir);
      if (options_.restart) snapshots_->resume(book_.snapshotTimes);
    }
    if (options_.progress) {
      io::Progress::Options o;
      o.label = "ecm-mpm " + scene_.name + " (implicit)";
      progress_ = std::make_unique<io::Progress>(total_, o);
    }
  }
  void output() {
    row({});
    if (snapshots_) snapshots_->add(solver_.particles(), book_.progress);
    book_.nextSnapshot = snapshotSpacing();
  }
  double snapshotSpacing() const { return scene_.outputInterval * scene_.snapshotEvery; }
  // A snapshot where the progress passes the next multiple of the spacing, and at the end.
  void snapshotIfDue() {
    if (!snapshots_) return;
    const bool end = book_.progress >= total_ * (1.0 - 1e-12);
    const double spacing = snapshotSpacing();
    if (!end && !(spacing > 0.0 && book_.progress >= book_.nextSnapshot * (1.0 - 1e-12))) return;
    snapshots_->add(solver_.particles(), book_.progress);
    while (spacing > 0.0 && book_.nextSnapshot <= book_.progress * (1.0 + 1e-12)) book_.nextSnapshot += spacing;
  }
  // A history row: the explicit columns (kinetic energy and damping 0), then the implicit ones.
  void row(const ImplicitStepReport& r) {
    std::vector<double> v{solver_.time(), static_cast<double>(solver_.steps())};
    for (const ConditionState& c : solver_.conditions()) v.insert(v.end(), {c.displacement[0], c.displacement[1], c.reaction[0], c.reaction[1]});
    for (const Load& l : scene_.loads) {
      const Vec2 f = l.force * l.history(solver_.time());
      v.insert(v.end(), {f[0], f[1]});
    }
    const Energies e = solver_.energies();
    v.insert(v.end(), {0.0, e.strain, e.externalWork, e.dissipated, 0.0, static_cast<double>(cracked()), solver_.loadFactor(),
                       static_cast<double>(r.totalIterations), static_cast<double>(r.cuts), static_cast<double>(r.released),
                       r.size, r.onsetOvershoot, solver_.internalWork(), solver_.internalWork() - e.strain,
                       static_cast<double>(r.relaxed)});
    history_->row(v);
    history_->flush();
  }
  long cracked() const {
    long n = 0;
    for (const auto b : solver_.particles().band) n += b >= 0 ? 1 : 0;
    return n;
  }
  void outputFailure(const io::OutputError& o) {
    result_.error = result_.error.empty() ? o.what() : result_.error + "; then: " + o.what();
    result_.completed = result_.stopped = false;
    outputFailed_ = true;
  }

  // --- checkpoint ---
  void readRestart() {
    book_ = readImplicitCheckpoint(checkpointFile_, solver_, options_.sceneHash);
    watch_.peak = book_.stopWatchPeak;
    result_.restartedFrom = solver_.steps();
    checkpointStep_ = solver_.steps();
  }
  bool checkpointDue() const {
    const CheckpointSettings& every = scene_.checkpoint;
    return (every.everySteps > 0 && solver_.steps() % every.everySteps == 0) ||
           (every.everyMinutes > 0.0 && secondsSince(lastCheckpoint_) >= 60.0 * every.everyMinutes);
  }
  void checkpoint() {
    if (checkpointStep_ == solver_.steps()) return;
    history_->flush();
    book_.history = {history_->bytes(), history_->digest(), history_->rows()};
    book_.stopWatchPeak = watch_.peak;
    if (snapshots_) book_.snapshotTimes = snapshots_->times();
    writeImplicitCheckpoint(checkpointFile_, solver_, book_, options_.sceneHash);
    checkpointStep_ = solver_.steps();
    lastCheckpoint_ = WallClock::now();
    ++result_.checkpoints;
  }

  // --- summary ---
  nlohmann::json summary() {
    result_.peakLoad = book_.peakLoad;
    nlohmann::json j;
    j["units"] = "mm, N, MPa, t, s (time: pseudo-time)";
    j["scene"] = scene_.name;
    j["scheme"] = "implicit_static";
    j["control"] = settings_.indirect ? "indirect" : "displacement";
    j["status"] = result_.completed ? "completed" : (result_.stopped ? "stopped" : "failed");
    if (!result_.error.empty()) j["error"] = result_.error;
    if (result_.stopped && !options_.resumeCommand.empty()) j["resume"] = options_.resumeCommand;
    if (result_.restartedFrom >= 0) j["restarted_from_step"] = result_.restartedFrom;
    j["steps"] = solver_.steps();
    if (result_.endedByStopWhen) j["ended_by_stop_when_at_load_N"] = result_.stopLoad;
    j["particles"] = result_.particles;
    j["peak_load"] = book_.peakLoad;  // N, as explicit runs name it
    j["load_factor"] = solver_.loadFactor();
    j["newton_iterations"] = book_.iterations;
    j["newton_iterations_per_step"] =
        solver_.steps() > 0 ? static_cast<double>(book_.iterations) / static_cast<double>(solver_.steps()) : 0.0;
    j["most_newton_iterations_in_a_step"] = book_.mostIterations;
    j["halvings"] = book_.halvings;
    j["factorizations"] = book_.factorizations;
    j["linear_solve_s"] = book_.linearSolveSeconds;
    j["linear_solver"] = settings_.umfpack ? "umfpack" : "sparselu";
    j["snap_back_releases"] = book_.released;
    j["relaxed_steps"] = book_.relaxed;  // kept with a residual between tolerance and accept_tolerance
    j["cracked_particles"] = cracked();
    const Energies e = solver_.energies();
    // Two dissipations (docs/implicit.md, "Energies"): the model's f int Y dD, and the internal
    // work minus the strain energy, which the external work balances step by step.
    j["energies_Nmm"] = {{"strain", e.strain},
                         {"external_work", e.externalWork},
                         {"internal_work", solver_.internalWork()},
                         {"dissipated", e.dissipated},
                         {"work_dissipated", solver_.internalWork() - e.strain}};
    j["energy_balance"] = std::abs(e.externalWork - solver_.internalWork()) / std::max(std::abs(e.externalWork), 1e-300);
    j["wall_time_s"] = result_.wallTime;
    j["threads"] = solver_.setup().threads;
    j["checkpoints_written"] = result_.checkpoints;
    return j;
  }

  const Scene& scene_;
  const ImplicitSettings& settings_;
  RunOptions options_;
  WallClock::time_point start_;
  ImplicitSolver solver_;
  std::filesystem::path checkpointFile_;
  WallClock::time_point lastCheckpoint_;
  IndirectControl control_;
  double from_ = 0.0, total_ = 0.0;
  StopWatch watch_;
  std::size_t watched_ = 0;
  int watchedComponent_ = 0;
  bool anyDriven_ = false, rowObserverAsksStop_ = false, outputFailed_ = false;
  long checkpointStep_ = -1;
  ImplicitBookkeeping book_;
  RunResult result_;
  std::unique_ptr<io::CsvWriter> history_;
  std::unique_ptr<VtuSeries> snapshots_;
  std::unique_ptr<io::Progress> progress_;
};

}  // namespace

RunResult runImplicitScene(const Scene& scene, const RunOptions& options) { return ImplicitRun(scene, options).execute(); }

}  // namespace ecm::mpm
