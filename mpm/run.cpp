#include "mpm/run.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <sstream>
#include <system_error>
#include <nlohmann/json.hpp>

#include "io/csv_writer.hpp"
#include "io/gnuplot.hpp"
#include "io/particle_map.hpp"
#include "io/json_summary.hpp"
#include "io/output_dir.hpp"
#include "io/output_error.hpp"
#include "io/progress.hpp"
#include "mpm/checkpoint.hpp"
#include "mpm/implicit_run.hpp"
#include "mpm/solver.hpp"
#include "mpm/vtu_writer.hpp"

namespace ecm::mpm {

std::unique_ptr<io::CsvWriter> openHistory(const std::filesystem::path& dir, const std::vector<std::string>& columns,
                                           const std::filesystem::path& checkpoint, const io::CsvWriter::Resume* resume) {
  if (!resume) {
    std::error_code ignored;  // a checkpoint of an earlier run in this folder no longer applies
    std::filesystem::remove(checkpoint, ignored);
    return std::make_unique<io::CsvWriter>(dir / "history.csv", columns);
  }
  try {
    return std::make_unique<io::CsvWriter>(dir / "history.csv", columns, *resume);
  } catch (const io::OutputError&) {
    throw;
  } catch (const std::runtime_error& e) {
    throw CheckpointError("cannot continue from checkpoint '" + checkpoint.string() + "': " + e.what());
  }
}

int drivenComponent(const NodeCondition& c) {
  return (c.component[1].kind == Prescribed::Velocity || c.component[1].kind == Prescribed::Displacement) &&
                 !(c.component[0].kind == Prescribed::Velocity || c.component[0].kind == Prescribed::Displacement)
             ? 1
             : 0;
}

namespace {

std::vector<double> historyRow(const Solver& s) {
  std::vector<double> row{s.time(), static_cast<double>(s.step())};
  for (const auto& c : s.conditions()) {
    row.insert(row.end(), {c.displacement[0], c.displacement[1], c.reaction[0], c.reaction[1]});
  }
  for (const auto& l : s.loads()) row.insert(row.end(), {l.applied[0], l.applied[1]});
  const Energies e = s.energies();
  row.insert(row.end(), {e.kinetic, e.strain, e.externalWork, e.dissipated, e.damping,
                         static_cast<double>(s.particles().bands.size())});
  return row;
}

}  // namespace

// The load-displacement curve: the first driven condition's displacement against its reaction,
// else the first load against time.
void plotLoadDisplacement(const Scene& scene, const std::filesystem::path& dir) {
  io::PlotSpec spec;
  spec.title = scene.name + ": load-displacement";
  const int base = 3;  // time, step, then 4 columns per condition (1-based gnuplot columns)
  for (std::size_t i = 0; i < scene.conditions.size(); ++i) {
    const auto& c = scene.conditions[i];
    if (!isDriven(c) || c.field) continue;
    const int d = drivenComponent(c);
    const int col = base + 4 * static_cast<int>(i);
    spec.xLabel = c.name + (d ? " u_y" : " u_x") + " (mm)";
    spec.yLabel = c.name + (d ? " reaction R_y" : " reaction R_x") + " (N)";
    spec.series.push_back({"history.csv", std::to_string(col + d) + ":" + std::to_string(col + 2 + d), "", c.name, "lines"});
    break;
  }
  if (spec.series.empty() && !scene.loads.empty()) {
    const int col = base + 4 * static_cast<int>(scene.conditions.size());
    const int d = scene.loads[0].force[1] != 0.0 ? 1 : 0;
    spec.xLabel = "time (s)";
    spec.yLabel = scene.loads[0].name + " (N)";
    spec.series.push_back({"history.csv", "1:" + std::to_string(col + d), "", scene.loads[0].name, "lines"});
  }
  if (spec.series.empty() && !scene.conditions.empty()) {  // e.g. a free vibration: the first reaction in time
    spec.title = scene.name + ": reaction";
    spec.xLabel = "time (s)";
    spec.yLabel = scene.conditions[0].name + " reaction R_x (N)";
    spec.series.push_back({"history.csv", "1:" + std::to_string(base + 2), "", scene.conditions[0].name, "lines"});
  }
  if (spec.series.empty()) return;
  io::renderPlot(spec, dir / "load_displacement.png");
}

// The final state of every particle (x, y, damage, material id, normal opening and normal of the
// band, stress), for damage and crack maps and the locking diagnosis.
// Written as PATH.tmp, then renamed: a restart rewrites it, and a reader never sees half of it.
void writeParticles(const Particles& p, const std::filesystem::path& path) {
  std::filesystem::path tmp = path;
  tmp += ".tmp";
  try {
    std::vector<std::string> columns{"x_mm", "y_mm", "damage", "material", "opening_mm", "normal_x", "normal_y",
                                     "sig_xx_MPa", "sig_yy_MPa", "sig_xy_MPa"};
    const bool twoBands = !p.secondBand.empty();  // second_band: orthogonal: the second band's columns
    if (twoBands)
      for (const char* c : {"damage_2", "opening_2_mm", "normal_x_2", "normal_y_2"}) columns.emplace_back(c);
    io::CsvWriter csv(tmp, columns);
    std::vector<double> row;
    for (std::size_t i = 0; i < p.size(); ++i) {
      const BandState* b = p.band[i] >= 0 ? &p.bands[static_cast<std::size_t>(p.band[i])] : nullptr;
      const Vec2 normal = b ? b->crackNormal : Vec2::Zero();
      row = {p.position[i][0], p.position[i][1], p.damage(i), static_cast<double>(p.material[i]),
             b ? b->normalJump() : 0.0, normal[0], normal[1], p.stress[i][0], p.stress[i][1], p.stress[i][2]};
      if (twoBands) {
        const BandState* b2 = p.secondBandOf(i);
        row.insert(row.end(), {b2 ? b2->damage() : 0.0, b2 ? b2->normalJump() : 0.0, b2 ? b2->crackNormal[0] : 0.0,
                               b2 ? b2->crackNormal[1] : 0.0});
      }
      csv.row(row);
    }
    csv.close();
  } catch (const io::OutputError& e) {
    std::error_code ignored;
    std::filesystem::remove(tmp, ignored);
    throw io::OutputError(path, e.reason);
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) throw io::OutputError(path, "rename from " + tmp.filename().string() + " failed: " + ec.message());
}

// The damage map of particles_final.csv: one square point per particle, coloured by damage, laid
// out for the grid's shape (io/particle_map.hpp: a slender bar is stretched, not a sliver).
void plotDamage(const Scene& scene, std::size_t particles, const std::filesystem::path& dir) {
  const Vec2 extent = scene.grid.extent();
  io::renderPlot(io::particleMapSpec({scene.name + ": damage at the end", "particles_final.csv", "1:2:3", "damage",
                                      extent[0], extent[1], particles}),
                 dir / "damage_map.png");
}

std::vector<std::string> historyColumns(const Scene& scene) {
  std::vector<std::string> h{"time_s", "step"};
  for (const auto& c : scene.conditions)
    for (const char* q : {"_ux_mm", "_uy_mm", "_rx_N", "_ry_N"}) h.push_back(c.name + q);
  for (const auto& l : scene.loads)
    for (const char* q : {"_fx_N", "_fy_N"}) h.push_back(l.name + q);
  for (const char* q : {"kinetic_Nmm", "strain_Nmm", "external_work_Nmm", "dissipated_Nmm", "damping_Nmm", "cracked"})
    h.push_back(q);
  return h;
}

namespace {

using WallClock = std::chrono::steady_clock;
double secondsSince(WallClock::time_point t) { return std::chrono::duration<double>(WallClock::now() - t).count(); }

// One run of a scene: the step loop and its parts, each a member function of its own:
//   output       a history row at every output step, a VTU snapshot at every snapshot_every-th
//                one and at the end, particle snapshots at the scene's times, the final particles;
//   checkpoint   when one is due (every N steps, M minutes, on a stop request) and what it
//                records of the run's bookkeeping besides the solver's state;
//   stop         the end time, the scene's stop_when (at an output row), a stop request
//                (signal, --max-steps).
// Then the summary and the plots.
class Run {
 public:
  Run(const Scene& scene, const RunOptions& options)
      : scene_(scene), options_(options), start_(WallClock::now()), solver_(scene, options.threads),
        checkpointFile_(checkpointPath(options.outputDir)), lastCheckpoint_(start_) {
    result_.particles = solver_.particles().size();
    if (options.restart) readRestart();  // before anything in the folder is touched
    io::prepareOutputDir(options.outputDir);
    openOutputs();
    if (scene.stopWhen) {
      watched_ = findCondition(scene.conditions, scene.stopWhen->condition).value();  // validated
      watchedComponent_ = drivenComponent(scene.conditions.at(watched_));
    }
    for (const auto& c : scene.conditions) anyDriven_ = anyDriven_ || isDriven(c);
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
      result_.error = e.what();
      try {
        output(true);  // the state at the failure (history row and snapshot), for a look at what went wrong
      } catch (const io::OutputError& o) {
        result_.error += std::string("; then: ") + o.what();
        outputFailed_ = true;
      }
    } catch (const io::OutputError& e) {
      // A file could not be written (full disk?): what is on disk stays readable (history.csv ends
      // with its last whole row, the other files are replaced atomically). Nothing more is written
      // but, if it can be, the summary.
      result_.error = std::string(e.what()) + " (at step " + std::to_string(solver_.step()) + ")";
      outputFailed_ = true;
    }
    if (progress_) progress_->finish();
    closeOutputs();
    result_.steps = solver_.step();
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
      plotDamage(scene_, solver_.particles().size(), options_.outputDir);
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
      solver_.advance();
      trackPeak();
      particleSnapshots();
      if (finished() || (scene_.outputInterval > 0.0 && solver_.time() >= nextOutput_ - 0.5 * solver_.timeStep())) {
        watchStop();
        output();
        if (options_.onRow && !options_.onRow(solver_.time(), solver_.step())) rowObserverAsksStop_ = true;
        while (scene_.outputInterval > 0.0 && nextOutput_ <= solver_.time() + 0.5 * solver_.timeStep())
          nextOutput_ += scene_.outputInterval;  // (output_interval 0: the last step only)
      }
      if (progress_) progress_->update(solver_.time());
      if (!finished() && checkpointDue()) checkpoint();
    }
  }

  // --- stop ---
  // (A half-step tolerance: round-off in the accumulated time adds no step.)
  bool finished() const {
    return result_.endedByStopWhen || solver_.time() >= scene_.endTime - 0.5 * solver_.timeStep();
  }
  bool stopRequested() const {
    return rowObserverAsksStop_ || (options_.stop && options_.stop->load(std::memory_order_relaxed)) ||
           (options_.maxSteps > 0 && solver_.step() >= options_.maxSteps);
  }
  // The scene's stop_when (mpm/stop_when.hpp), at an output row, before it is written.
  void watchStop() {
    if (!scene_.stopWhen) return;
    const double load = solver_.conditions()[watched_].reaction[watchedComponent_];
    if (watch_.observe(*scene_.stopWhen, solver_.time(), load)) {
      result_.endedByStopWhen = true;
      result_.stopLoad = load;
    }
  }
  // The peak of the driven conditions' reactions (all conditions' if none is driven) and loads.
  void trackPeak() {
    for (std::size_t i = 0; i < scene_.conditions.size(); ++i)
      if (isDriven(scene_.conditions[i]) || !anyDriven_)
        result_.peakLoad = std::max(result_.peakLoad, solver_.conditions()[i].reaction.norm());
    for (const auto& l : solver_.loads()) result_.peakLoad = std::max(result_.peakLoad, l.applied.norm());
  }

  // --- output ---
  void openOutputs() {
    const std::filesystem::path& dir = options_.outputDir;
    history_ = openHistory(dir, historyColumns(scene_), checkpointFile_, options_.restart ? &book_.history : nullptr);
    if (options_.snapshots) {
      snapshots_ = std::make_unique<VtuSeries>(dir);
      if (options_.restart) snapshots_->resume(book_.snapshotTimes);
    }
    if (options_.progress) {
      io::Progress::Options o;
      o.label = "ecm-mpm " + scene_.name;
      progress_ = std::make_unique<io::Progress>(scene_.endTime, o);
    }
  }
  // A history row; a VTU snapshot at row 0, N, 2N, ... (N = snapshot_every) and at the end. The
  // row count survives a restart, so the series goes on in step.
  void output(bool forceSnapshot = false) {
    const std::size_t row = history_->rows();
    history_->row(historyRow(solver_));
    history_->flush();
    if (snapshots_ && (forceSnapshot || row % static_cast<std::size_t>(scene_.snapshotEvery) == 0 || finished()))
      snapshots_->add(solver_);
  }
  // particles_t<time>.csv at the scene's times, the first step at or past each.
  void particleSnapshots() {
    const auto& times = scene_.particleSnapshots;
    for (; nextSnapshot_ < times.size() && solver_.time() >= times[nextSnapshot_] - 0.5 * solver_.timeStep(); ++nextSnapshot_) {
      std::ostringstream name;
      name << "particles_t" << times[nextSnapshot_] << ".csv";
      writeParticles(solver_.particles(), options_.outputDir / name.str());
    }
  }
  // What goes wrong from here on is added to the result; what was written stays readable.
  void outputFailure(const io::OutputError& o) {
    result_.error = result_.error.empty() ? o.what() : result_.error + "; then: " + o.what();
    result_.completed = result_.stopped = false;
    outputFailed_ = true;
  }
  void closeOutputs() {
    try {
      if (!outputFailed_) history_->close();
      if (!outputFailed_) writeParticles(solver_.particles(), options_.outputDir / "particles_final.csv");  // also after a failure or a stop
    } catch (const io::OutputError& o) {
      outputFailure(o);
    }
  }

  // --- checkpoint ---
  void readRestart() {
    book_ = readCheckpoint(checkpointFile_, solver_, options_.sceneHash);
    result_.restartedFrom = solver_.step();
    // Particle snapshots behind the checkpoint are done.
    while (nextSnapshot_ < scene_.particleSnapshots.size() &&
           solver_.time() >= scene_.particleSnapshots[nextSnapshot_] - 0.5 * solver_.timeStep())
      ++nextSnapshot_;
    nextOutput_ = book_.nextOutput;
    result_.peakLoad = book_.peakLoad;
    watch_.peak = book_.stopWatchPeak;
    checkpointStep_ = solver_.step();
  }
  bool checkpointDue() const {
    const CheckpointSettings& every = scene_.checkpoint;
    return (every.everySteps > 0 && solver_.step() % every.everySteps == 0) ||
           (every.everyMinutes > 0.0 && secondsSince(lastCheckpoint_) >= 60.0 * every.everyMinutes);
  }
  void checkpoint() {
    if (checkpointStep_ == solver_.step()) return;
    history_->flush();
    book_.nextOutput = nextOutput_;
    book_.peakLoad = result_.peakLoad;
    book_.stopWatchPeak = watch_.peak;
    book_.history = {history_->bytes(), history_->digest(), history_->rows()};
    if (snapshots_) book_.snapshotTimes = snapshots_->times();
    writeCheckpoint(checkpointFile_, solver_, book_, options_.sceneHash);
    checkpointStep_ = solver_.step();
    lastCheckpoint_ = WallClock::now();
    ++result_.checkpoints;
  }

  // --- summary ---
  nlohmann::json summary() const {
    const Energies e = solver_.energies();
    const Particles& p = solver_.particles();
    const RunResult& r = result_;
    nlohmann::json j = {
        {"scene", scene_.name},
        {"status", r.completed ? "completed" : (r.stopped ? "stopped" : "failed")},
        {"peak_load", r.peakLoad},
        {"wall_time_s", r.wallTime},
        {"steps", r.steps},
        {"particles", r.particles},
        {"cracked_particles", p.bands.size()},
        {"bytes_per_particle_uncracked", p.bytesPerParticle()},
        {"bytes_per_particle_cracked", p.bytesPerParticle() + p.bytesPerBand()},
        {"time_step_s", solver_.timeStep()},
        {"end_time_s", solver_.time()},
        {"threads", solver_.threads()},
        {"preset", scene_.preset.empty() ? "none" : scene_.preset},
        {"particles_per_cell", scene_.particlesPerCell},
        {"cfl", scene_.solver.cfl},
        {"scheme", toString(scene_.solver.scheme)},
        {"shape_function", toString(scene_.solver.shapeFunction)},
        {"substepped_updates", solver_.substepped()},
        {"snap_back_releases", solver_.snapBackReleases()},
        {"particle_updates_per_s",  // of this run's steps (after a restart: those since the checkpoint)
         r.wallTime > 0.0 ? static_cast<double>(r.particles) *
                                static_cast<double>(r.steps - std::max(r.restartedFrom, 0L)) / r.wallTime
                          : 0.0},
        {"energies_Nmm",
         {{"kinetic", e.kinetic}, {"strain", e.strain}, {"external_work", e.externalWork}, {"dissipated", e.dissipated},
          {"damping", e.damping}}},
        {"checkpoints_written", r.checkpoints},
        {"units", "mm, N, MPa, t, s"}};
    if (scene_.stopWhen) {
      const StopWhen& w = *scene_.stopWhen;
      j["stop_when"] = {{"condition", w.condition},
                        {"load_below", w.loadBelow},
                        {"after_time_s", w.afterTime},
                        {"met", r.endedByStopWhen},
                        {"peak_of_rows_N", watch_.peak}};
      if (r.endedByStopWhen) j["stop_when"]["load_at_stop_N"] = r.stopLoad;
    }
    if (!p.secondBand.empty()) {  // second_band: orthogonal (docs/model.md)
      j["two_band_points"] = p.twoBandPoints();
      j["bytes_per_particle_two_bands"] = p.bytesPerParticle() + 2 * p.bytesPerBand();
    }
    // Where the steps' wall time went (of this run's steps: after a restart, those since the checkpoint).
    nlohmann::json phases = nlohmann::json::object();
    for (std::size_t k = 0; k < kStepPhases; ++k)
      if (const double t = solver_.phaseSeconds(static_cast<StepPhase>(k)); t > 0.0) phases[toString(static_cast<StepPhase>(k))] = t;
    j["phase_seconds"] = phases;
    if (!r.completed && !r.stopped) j["error"] = r.error;
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
  const WallClock::time_point start_;
  Solver solver_;  // throws on a scene it cannot seed, before any output
  const std::filesystem::path checkpointFile_;
  RunResult result_;
  RunBookkeeping book_;
  // output
  std::unique_ptr<io::CsvWriter> history_;
  std::unique_ptr<VtuSeries> snapshots_;
  std::unique_ptr<io::Progress> progress_;
  double nextOutput_ = scene_.outputInterval;
  std::size_t nextSnapshot_ = 0;
  bool outputFailed_ = false;
  bool rowObserverAsksStop_ = false;  // RunOptions::onRow returned false
  // stop
  StopWatch watch_;
  std::size_t watched_ = 0;
  int watchedComponent_ = 0;
  bool anyDriven_ = false;
  // checkpoint
  long checkpointStep_ = -1;  // the step of the checkpoint on disk
  WallClock::time_point lastCheckpoint_;
};

}  // namespace

RunResult runScene(const Scene& scene, const RunOptions& options) {
  if (scene.solver.implicit) return runImplicitScene(scene, options);
  return Run(scene, options).execute();
}

}  // namespace ecm::mpm
