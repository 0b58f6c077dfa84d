// The one run loop of both solvers (mpm/run_loop.hpp).
#include "mpm/run_loop.hpp"

#include <algorithm>
#include <chrono>
#include <memory>
#include <sstream>
#include <system_error>

#include "io/csv_writer.hpp"
#include "io/json_summary.hpp"
#include "io/output_dir.hpp"
#include "io/output_error.hpp"
#include "io/progress.hpp"
#include "mpm/core/errors.hpp"
#include "mpm/output/run_files.hpp"
#include "mpm/output/vtu_writer.hpp"
#include "mpm/scene/stop_when.hpp"
#include "mpm/setup/gauge_points.hpp"

namespace ecm::mpm {

namespace {

// The tracked crack paths (crack_paths.csv: per arm its points from the root to the tip, then the
// end of its look-ahead as a row with `ahead` 1; docs/model.md, "Crack paths").
void writeCrackPaths(const CrackPaths& paths, const std::filesystem::path& path) {
  writeCsvAtomically(path, {"arm", "point", "x_mm", "y_mm", "ahead"}, [&](io::CsvWriter& csv) {
    for (std::size_t a = 0; a < paths.arms().size(); ++a) {
      const CrackArm& arm = paths.arms()[a];
      for (std::size_t k = 0; k < arm.points.size(); ++k)
        csv.row({static_cast<double>(a), static_cast<double>(k), arm.points[k][0], arm.points[k][1], 0.0});
      const Vec2 ahead = arm.points.back() + paths.geometry().lookAhead * arm.direction;
      csv.row({static_cast<double>(a), static_cast<double>(arm.points.size()), ahead[0], ahead[1], 1.0});
    }
  });
}

// summary.json's "failure": the kind, ecm-mpm's exit status, where and when (docs/tools.md,
// "When a run fails").
nlohmann::json failureJson(const RunFailure& f) {
  nlohmann::json j = {{"kind", toString(f.kind)}, {"exit_status", exitStatusOf(f.kind)}, {"step", f.step}};
  if (f.particle) j["particle"] = *f.particle;
  if (f.position) j["position_mm"] = {(*f.position)[0], (*f.position)[1]};
  if (f.kind == FailureKind::MaterialFailure || f.kind == FailureKind::SnapBack) j["material_status"] = toString(f.materialStatus);
  if (f.residual != 0.0) j["residual"] = f.residual;
  if (f.likelyLimitPoint) j["likely_limit_point"] = true;
  if (!f.file.empty()) j["file"] = f.file.string();
  return j;
}

using WallClock = std::chrono::steady_clock;
double secondsSince(WallClock::time_point t) { return std::chrono::duration<double>(WallClock::now() - t).count(); }

// One run, its parts each a member function of its own:
//   loop        a step, the peak, the particle snapshots, a history row when one is due (with
//               the stop_when watch and a VTU snapshot when one is due), a checkpoint when due
//   stop        the end, the scene's stop_when (at a row), a stop request (signal, --max-steps,
//               the row callback)
//   output      history.csv, VTU snapshots, particle snapshots, the final particles; a file that
//               cannot be written ends the output, not the account of it
//   checkpoint  when one is due (every N steps, M minutes, on a stop request) and the loop's book
// Then the summary and the plots.
class RunLoop {
 public:
  RunLoop(const Scene& scene, const RunOptions& options, Stepper& stepper)
      : scene_(scene), options_(options), stepper_(stepper), start_(WallClock::now()),
        checkpointFile_(checkpointPath(options.outputDir)), lastCheckpoint_(start_) {
    result_.particles = stepper.particles().size();
    gaugePoints_ = locateGauges(scene, stepper.particles());  // from the seed positions: also after a restart
    platenPeaks_.assign(scene.platens.size(), Eigen::Vector3d::Zero());
    if (options.restart) readRestart();  // before anything in the folder is touched
    io::prepareOutputDir(options.outputDir);
    openOutputs();
    if (scene.stopWhen && scene.stopWhen->gauge.empty()) {
      watched_ = findCondition(scene.conditions, scene.stopWhen->condition).value();  // validated
      watchedComponent_ = drivenComponent(scene.conditions.at(watched_));
    }
    for (const auto& c : scene.conditions) anyDriven_ = anyDriven_ || isDriven(c);
    for (const auto& p : scene.platens) anyDriven_ = anyDriven_ || displacementDriven(p, kPlatenX) || displacementDriven(p, kPlatenY);
  }

  RunResult execute() {
    try {
      if (!options_.restart) {
        watchStop();
        output();
      }
      stepLoop();
      result_.completed = !result_.stopped;
    } catch (const SimulationError& e) {
      result_.failure = e.failure();
      try {
        if (stepper_.failureKeepsConsistentState())
          checkpoint();  // the last consistent state, to continue from or look at
        else
          output(true);  // the state at the failure (history row and snapshot), for a look at what went wrong
      } catch (const io::OutputError& o) {
        outputFailure(o);
      }
    } catch (const io::OutputError& e) {
      // A file could not be written (full disk?): what is on disk stays readable (history.csv ends
      // with its last whole row, the other files are replaced atomically). Nothing more is written
      // but, if it can be, the summary.
      result_.failure = outputFailureOf(std::string(e.what()) + " (at step " + std::to_string(stepper_.steps()) + ")",
                                      stepper_.steps(), e.path);
      outputFailed_ = true;
    }
    if (progress_) progress_->finish();
    closeOutputs();
    result_.steps = stepper_.steps();
    result_.wallTime = secondsSince(start_);
    std::error_code ec;
    if (result_.completed) std::filesystem::remove(checkpointFile_, ec);  // it describes an unfinished run
    if (std::filesystem::exists(checkpointFile_, ec)) result_.checkpoint = checkpointFile_;
    try {
      io::writeJsonSummary(summary(), options_.outputDir / "summary.json");
    } catch (const io::OutputError& o) {  // the old summary, if any, stays whole
      outputFailure(o);
    }
    if (!outputFailed_ && options_.plot && !result_.stopped) {
      plotLoadDisplacement(scene_, options_.outputDir);
      plotDamage(scene_, stepper_.particles().size(), options_.outputDir);
    }
    return result_;
  }

 private:
  // --- the loop ---
  void stepLoop() {
    while (!finished()) {
      if (stopRequested()) {
        checkpoint();
        result_.stopped = true;
        break;
      }
      stepper_.advance();
      trackPeak();
      particleSnapshots();
      if (stepper_.reachedEnd() || stepper_.rowDue()) {
        watchStop();
        output();
        if (options_.onRow && !options_.onRow(stepper_.time(), stepper_.steps())) rowObserverAsksStop_ = true;
        stepper_.rowWritten();
      }
      if (progress_) progress_->update(stepper_.progress());
      if (!finished() && checkpointDue()) checkpoint();
    }
  }

  // --- stop ---
  bool finished() const { return result_.endedByStopWhen || stepper_.reachedEnd(); }
  bool stopRequested() const {
    return rowObserverAsksStop_ || (options_.stop && options_.stop->load(std::memory_order_relaxed)) ||
           (options_.maxSteps > 0 && stepper_.steps() >= options_.maxSteps);
  }
  // The scene's stop_when (mpm/scene/stop_when.hpp), at a history row.
  void watchStop() {
    if (!scene_.stopWhen) return;
    if (!scene_.stopWhen->gauge.empty()) {  // a gauge that reaches its value
      const double reading = std::abs(gaugeReading(scene_.stopWhen->gauge));
      if (stepper_.progress() >= scene_.stopWhen->afterTime && reading >= scene_.stopWhen->gaugeReaches) {
        result_.endedByStopWhen = true;
        result_.stopLoad = 0.0;  // (a gauge stop has no load)
      }
      return;
    }
    const double load = stepper_.conditions()[watched_].reaction[watchedComponent_];
    if (watch_.observe(*scene_.stopWhen, stepper_.progress(), load)) {
      result_.endedByStopWhen = true;
      result_.stopLoad = load;
    }
  }
  // The peak of the driven conditions' reactions (all conditions' if none is driven) and loads.
  void trackPeak() {
    for (std::size_t i = 0; i < scene_.conditions.size(); ++i)
      if (isDriven(scene_.conditions[i]) || !anyDriven_)
        result_.peakLoad = std::max(result_.peakLoad, stepper_.conditions()[i].reaction.norm());
    for (const Vec2& f : stepper_.appliedLoads()) result_.peakLoad = std::max(result_.peakLoad, f.norm());
    for (std::size_t i = 0; i < scene_.platens.size(); ++i) {  // a platen's force on its driven translations
      const Eigen::Vector3d& f = stepper_.platens()[i].force;
      platenPeaks_[i] = platenPeaks_[i].cwiseMax(f.cwiseAbs());
      const Platen& p = scene_.platens[i];
      const Vec2 driven(displacementDriven(p, kPlatenX) ? f[0] : 0.0, displacementDriven(p, kPlatenY) ? f[1] : 0.0);
      result_.peakLoad = std::max(result_.peakLoad, driven.norm());
    }
  }

  // --- platens (mpm/scene/platen.hpp) and gauges (mpm/scene/gauge.hpp): their columns after the solver's ---
  double gaugeReading(const std::string& name) const {
    for (std::size_t g = 0; g < scene_.gauges.size(); ++g)
      if (scene_.gauges[g].name == name) return mpm::gaugeReading(scene_.gauges[g], gaugePoints_[g], stepper_.kinematics());
    return 0.0;  // (validated: the name is a gauge's)
  }
  std::vector<std::string> historyColumns() const {
    std::vector<std::string> columns = stepper_.historyColumns();
    for (const Platen& p : scene_.platens)
      for (const char* c : {"_ux_mm", "_uy_mm", "_rotation_rad", "_Fx_N", "_Fy_N", "_M_Nmm"}) columns.push_back(p.name + c);
    for (const Gauge& g : scene_.gauges) columns.push_back(g.name + "_mm");
    if (stepper_.crackPaths().tracked())  // what the rule holds intact off the paths (docs/model.md, "Crack paths")
      for (const char* c : {"held_past_onset", "held_max_overstress"}) columns.emplace_back(c);
    return columns;
  }
  std::vector<double> historyRow() const {
    std::vector<double> row = stepper_.historyRow();
    for (const PlatenState& p : stepper_.platens()) {
      row.insert(row.end(), p.displacement.data(), p.displacement.data() + 3);
      row.insert(row.end(), p.force.data(), p.force.data() + 3);
    }
    for (std::size_t g = 0; g < scene_.gauges.size(); ++g)
      row.push_back(mpm::gaugeReading(scene_.gauges[g], gaugePoints_[g], stepper_.kinematics()));
    if (const CrackPaths& paths = stepper_.crackPaths(); paths.tracked())
      row.insert(row.end(), {static_cast<double>(paths.held().count), paths.held().largestOverstress});
    return row;
  }

  // --- output ---
  void openOutputs() {
    const std::filesystem::path& dir = options_.outputDir;
    history_ = openHistory(dir, historyColumns(), checkpointFile_, options_.restart ? &stepper_.book().history : nullptr);
    if (options_.snapshots) {
      snapshots_ = std::make_unique<VtuSeries>(dir);
      if (options_.restart) snapshots_->resume(stepper_.book().snapshotTimes);
    }
    if (options_.progress) {
      io::Progress::Options o;
      o.label = stepper_.progressLabel();
      progress_ = std::make_unique<io::Progress>(stepper_.progressEnd(), o);
    }
  }
  // A history row, and a VTU snapshot when the stepper says so, at the end and on `force`. The
  // row count survives a restart, so the series goes on in step.
  void output(bool forceSnapshot = false) {
    if (!forceSnapshot) stepper_.checkEnergy();  // (a failure's row is written by the catch)
    const std::size_t row = history_->rows();
    history_->row(historyRow());
    history_->flush();
    if (snapshots_ && (forceSnapshot || stepper_.snapshotDue(row) || finished())) snapshot();
  }
  void snapshot() {
    snapshots_->add(stepper_.particles(), stepper_.progress());
    stepper_.snapshotTaken();
  }
  // particles_t<time>.csv at the scene's times, the first step at or past each.
  void particleSnapshots() {
    const auto& times = scene_.particleSnapshots;
    for (; nextParticleSnapshot_ < times.size() &&
           stepper_.progress() >= times[nextParticleSnapshot_] - stepper_.progressTolerance();
         ++nextParticleSnapshot_) {
      std::ostringstream name;
      name << "particles_t" << times[nextParticleSnapshot_] << ".csv";
      writeParticles(stepper_.particles(), options_.outputDir / name.str());
    }
  }
  // What goes wrong from here on is added to the result; what was written stays readable.
  void outputFailure(const io::OutputError& o) {
    if (result_.failure)  // the first failure keeps its kind
      result_.failure->message += std::string("; then: ") + o.what();
    else
      result_.failure = outputFailureOf(o.what(), stepper_.steps(), o.path);
    result_.completed = result_.stopped = false;
    outputFailed_ = true;
  }
  void closeOutputs() {
    try {
      if (outputFailed_) return;
      if (snapshots_ && !result_.completed && stepper_.failureKeepsConsistentState()) snapshot();  // where it stopped
      history_->close();
      writeParticles(stepper_.particles(), options_.outputDir / "particles_final.csv");  // also after a failure or a stop
      if (stepper_.crackPaths().tracked()) writeCrackPaths(stepper_.crackPaths(), options_.outputDir / "crack_paths.csv");
    } catch (const io::OutputError& o) {
      outputFailure(o);
    }
  }

  // --- checkpoint ---
  void readRestart() {
    stepper_.readCheckpoint(checkpointFile_, options_.sceneHash);
    const RunBook& book = stepper_.book();
    result_.restartedFrom = stepper_.steps();
    result_.peakLoad = book.peakLoad;
    watch_.peak = book.stopWatchPeak;
    if (book.platenPeaks.size() != platenPeaks_.size())
      throw CheckpointError("checkpoint '" + checkpointFile_.string() + "': it has the peaks of " +
                            std::to_string(book.platenPeaks.size()) + " platens, the scene " +
                            std::to_string(platenPeaks_.size()));
    platenPeaks_ = book.platenPeaks;
    checkpointStep_ = stepper_.steps();
    // Particle snapshots behind the checkpoint are done.
    while (nextParticleSnapshot_ < scene_.particleSnapshots.size() &&
           stepper_.progress() >= scene_.particleSnapshots[nextParticleSnapshot_] - stepper_.progressTolerance())
      ++nextParticleSnapshot_;
  }
  bool checkpointDue() const {
    const CheckpointSettings& every = scene_.checkpoint;
    return (every.everySteps > 0 && stepper_.steps() % every.everySteps == 0) ||
           (every.everyMinutes > 0.0 && secondsSince(lastCheckpoint_) >= 60.0 * every.everyMinutes);
  }
  void checkpoint() {
    if (checkpointStep_ == stepper_.steps()) return;
    history_->flush();
    RunBook& book = stepper_.book();
    book.peakLoad = result_.peakLoad;
    book.stopWatchPeak = watch_.peak;
    book.platenPeaks = platenPeaks_;
    book.history = {history_->bytes(), history_->digest(), history_->rows()};
    if (snapshots_) book.snapshotTimes = snapshots_->times();
    stepper_.writeCheckpoint(checkpointFile_, options_.sceneHash);
    checkpointStep_ = stepper_.steps();
    lastCheckpoint_ = WallClock::now();
    ++result_.checkpoints;
  }

  // --- summary: the solver's keys, then the common ones ---
  nlohmann::json summary() const {
    const RunResult& r = result_;
    nlohmann::json j = stepper_.summary(r);
    j["scene"] = scene_.name;
    j["status"] = r.completed ? "completed" : (r.stopped ? "stopped" : "failed");
    j["peak_load"] = r.peakLoad;  // N
    j["wall_time_s"] = r.wallTime;
    j["steps"] = r.steps;
    j["particles"] = r.particles;
    j["checkpoints_written"] = r.checkpoints;
    if (!scene_.gauges.empty()) {  // the material points each gauge follows (the seeds nearest to its points)
      nlohmann::json gauges = nlohmann::json::array();
      const Particles& p = stepper_.particles();
      for (std::size_t g = 0; g < scene_.gauges.size(); ++g) {
        const GaugePoints& at = gaugePoints_[g];
        nlohmann::json one = {{"name", scene_.gauges[g].name}, {"at_mm", {p.origin[at.at][0], p.origin[at.at][1]}}};
        if (scene_.gauges[g].to) one["to_mm"] = {p.origin[at.to][0], p.origin[at.to][1]};
        one["final_mm"] = mpm::gaugeReading(scene_.gauges[g], at, p);
        gauges.push_back(one);
      }
      j["gauges"] = gauges;
    }
    if (!scene_.platens.empty()) {  // where each platen ended and the largest force it put on the specimen
      nlohmann::json platens = nlohmann::json::array();
      for (std::size_t i = 0; i < scene_.platens.size(); ++i) {
        const PlatenState& p = stepper_.platens()[i];
        platens.push_back({{"name", scene_.platens[i].name},
                           {"reference_mm", {p.reference[0], p.reference[1]}},
                           {"nodes", p.nodes.size()},
                           {"final_displacement", {p.displacement[0], p.displacement[1], p.displacement[2]}},
                           {"final_force", {p.force[0], p.force[1], p.force[2]}},
                           {"peak_abs_force", {platenPeaks_[i][0], platenPeaks_[i][1], platenPeaks_[i][2]}}});
      }
      j["platens"] = platens;  // displacements mm, mm, rad; forces N, N, N mm
    }
    if (scene_.stopWhen && !scene_.stopWhen->gauge.empty()) {
      j["stop_when"] = {{"gauge", scene_.stopWhen->gauge}, {"reaches_mm", scene_.stopWhen->gaugeReaches}, {"met", r.endedByStopWhen}};
    } else if (scene_.stopWhen) {
      const StopWhen& w = *scene_.stopWhen;
      j["stop_when"] = {{"condition", w.condition},
                        {"load_below", w.loadBelow},
                        {"after_time_s", w.afterTime},
                        {"met", r.endedByStopWhen},
                        {"peak_of_rows_N", watch_.peak}};
      if (r.endedByStopWhen) j["stop_when"]["load_at_stop_N"] = r.stopLoad;
    }
    if (r.failure) {
      j["error"] = r.failure->message;
      j["failure"] = failureJson(*r.failure);
    }
    if (r.restartedFrom >= 0) j["restarted_from_step"] = r.restartedFrom;
    if (!r.checkpoint.empty()) {
      j["checkpoint"] = r.checkpoint.string();
      j["checkpoint_step"] = checkpointStep_;
    }
    if (r.stopped && !options_.resumeCommand.empty()) j["resume"] = options_.resumeCommand;
    return j;
  }

  const Scene& scene_;
  const RunOptions& options_;
  Stepper& stepper_;
  const WallClock::time_point start_;
  const std::filesystem::path checkpointFile_;
  RunResult result_;
  // output
  std::unique_ptr<io::CsvWriter> history_;
  std::unique_ptr<VtuSeries> snapshots_;
  std::unique_ptr<io::Progress> progress_;
  std::size_t nextParticleSnapshot_ = 0;
  bool outputFailed_ = false;
  bool rowObserverAsksStop_ = false;  // RunOptions::onRow returned false
  // stop
  StopWatch watch_;
  std::size_t watched_ = 0;
  int watchedComponent_ = 0;
  bool anyDriven_ = false;
  std::vector<GaugePoints> gaugePoints_;
  std::vector<Eigen::Vector3d> platenPeaks_;  // per platen: the largest |force| of each degree of freedom so far
  // checkpoint
  long checkpointStep_ = -1;  // the step of the checkpoint on disk
  WallClock::time_point lastCheckpoint_;
};

}  // namespace

RunResult runLoop(const Scene& scene, const RunOptions& options, Stepper& stepper) {
  return RunLoop(scene, options, stepper).execute();
}

}  // namespace ecm::mpm
