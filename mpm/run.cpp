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
#include "io/json_summary.hpp"
#include "io/output_dir.hpp"
#include "io/output_error.hpp"
#include "io/progress.hpp"
#include "mpm/checkpoint.hpp"
#include "mpm/solver.hpp"
#include "mpm/vtu_writer.hpp"

namespace ecm::mpm {

namespace {

bool driven(const NodeCondition& c) {
  if (c.field) return true;
  for (const auto& k : c.component)
    if (k.kind == Prescribed::Velocity || k.kind == Prescribed::Displacement) return true;
  return false;
}

// The component a driven condition loads along (the first prescribed one), for plots and peaks.
int drivenComponent(const NodeCondition& c) {
  return (c.component[1].kind == Prescribed::Velocity || c.component[1].kind == Prescribed::Displacement) &&
                 !(c.component[0].kind == Prescribed::Velocity || c.component[0].kind == Prescribed::Displacement)
             ? 1
             : 0;
}

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

// The load-displacement curve: the first driven condition's displacement against its reaction,
// else the first load against time.
void plot(const Scene& scene, const std::filesystem::path& dir) {
  io::PlotSpec spec;
  spec.title = scene.name + ": load-displacement";
  const int base = 3;  // time, step, then 4 columns per condition (1-based gnuplot columns)
  for (std::size_t i = 0; i < scene.conditions.size(); ++i) {
    const auto& c = scene.conditions[i];
    if (!driven(c) || c.field) continue;
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
void writeParticles(const Solver& s, const std::filesystem::path& path) {
  std::filesystem::path tmp = path;
  tmp += ".tmp";
  try {
    const Particles& p = s.particles();
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
      row = {p.position[i][0], p.position[i][1], s.damage(i), static_cast<double>(p.material[i]),
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

// The damage map of particles_final.csv: one square point per particle, coloured by damage.
void plotDamage(const Scene& scene, std::size_t particles, const std::filesystem::path& dir) {
  const double size = std::clamp(0.35 * std::sqrt(25000.0 / static_cast<double>(std::max<std::size_t>(particles, 1))), 0.05, 1.0);
  io::PlotSpec spec;
  spec.title = scene.name + ": damage at the end";
  spec.xLabel = "x (mm)";
  spec.yLabel = "y (mm)";
  spec.width = 800;
  spec.height = 760;
  spec.functions = {"set size ratio -1", "set cbrange [0:1]", "set cblabel 'damage'",
                    "set palette defined (0 '#f2f2f2', 0.3 '#9ecae1', 0.7 '#de2d26', 1 '#67000d')", "unset grid"};
  spec.series.push_back({"particles_final.csv", "1:2:3", "", "", "points pt 5 ps " + std::to_string(size) + " lc palette"});
  io::renderPlot(spec, dir / "damage_map.png");
}

}  // namespace

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

RunResult runScene(const Scene& scene, const RunOptions& options) {
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  auto seconds = [&](Clock::time_point since) { return std::chrono::duration<double>(Clock::now() - since).count(); };
  Solver solver(scene, options.threads);  // throws on an invalid scene, before any output
  const std::filesystem::path& dir = options.outputDir;
  const std::filesystem::path checkpointFile = checkpointPath(dir);
  RunResult result;
  result.particles = solver.particles().size();

  // A restart reads its checkpoint before anything in the folder is touched.
  RunBookkeeping book;
  if (options.restart) {
    book = readCheckpoint(checkpointFile, solver, options.sceneHash);
    result.restartedFrom = solver.step();
    if (book.threads != solver.threads())
      std::fprintf(stderr,
                   "warning: %s was written on %d threads, the run goes on on %d: the results agree with an "
                   "uninterrupted run to round-off, not bitwise\n",
                   checkpointFile.string().c_str(), book.threads, solver.threads());
  }
  io::prepareOutputDir(dir);
  std::unique_ptr<io::CsvWriter> history;
  if (options.restart) {
    try {
      history = std::make_unique<io::CsvWriter>(dir / "history.csv", historyColumns(scene), book.history);
    } catch (const io::OutputError&) {
      throw;
    } catch (const std::runtime_error& e) {
      throw CheckpointError("cannot continue from checkpoint '" + checkpointFile.string() + "': " + e.what());
    }
  } else {
    std::error_code ignored;  // a checkpoint of an earlier run in this folder no longer applies
    std::filesystem::remove(checkpointFile, ignored);
    history = std::make_unique<io::CsvWriter>(dir / "history.csv", historyColumns(scene));
  }
  std::unique_ptr<VtuSeries> snapshots;
  if (options.snapshots) {
    snapshots = std::make_unique<VtuSeries>(dir);
    if (options.restart) snapshots->resume(book.snapshotTimes);
  }
  std::unique_ptr<io::Progress> progress;
  if (options.progress) {
    io::Progress::Options o;
    o.label = "ecm-mpm " + scene.name;
    progress = std::make_unique<io::Progress>(scene.endTime, o);
  }

  // A history row at every output step; a VTU snapshot at every snapshot_every-th one (row 0, N,
  // 2N, ...) and at the end. The row count survives a restart, so the series goes on in step.
  // (A half-step tolerance in finished(): round-off in the accumulated time adds no step.)
  // The scene's stop_when (mpm/stop_when.hpp) ends it earlier, at an output row.
  auto finished = [&] { return result.endedByStopWhen || solver.time() >= scene.endTime - 0.5 * solver.timeStep(); };
  StopWatch watch;
  std::size_t watched = 0;
  int watchedComponent = 0;
  if (scene.stopWhen) {
    watched = findCondition(scene.conditions, scene.stopWhen->condition).value();  // validated
    watchedComponent = drivenComponent(scene.conditions.at(watched));
  }
  auto watchStop = [&] {  // at an output row, before it is written
    if (!scene.stopWhen) return;
    const double load = solver.conditions()[watched].reaction[watchedComponent];
    if (watch.observe(*scene.stopWhen, solver.time(), load)) {
      result.endedByStopWhen = true;
      result.stopLoad = load;
    }
  };
  auto output = [&](bool forceSnapshot = false) {
    const std::size_t row = history->rows();
    history->row(historyRow(solver));
    history->flush();
    if (snapshots && (forceSnapshot || row % static_cast<std::size_t>(scene.snapshotEvery) == 0 || finished()))
      snapshots->add(solver);
  };
  // The peak of the driven conditions' reactions (all conditions' if none is driven) and loads.
  bool anyDriven = false;
  for (const auto& c : scene.conditions) anyDriven = anyDriven || driven(c);
  auto trackPeak = [&] {
    for (std::size_t i = 0; i < scene.conditions.size(); ++i)
      if (driven(scene.conditions[i]) || !anyDriven)
        result.peakLoad = std::max(result.peakLoad, solver.conditions()[i].reaction.norm());
    for (const auto& l : solver.loads()) result.peakLoad = std::max(result.peakLoad, l.applied.norm());
  };

  double nextOutput = scene.outputInterval;
  // Particle snapshots (particles_t<time>.csv) at the scene's times, the first step at or past each;
  // after a restart, those already behind the checkpoint are done.
  std::size_t nextSnapshot = 0;
  auto particleSnapshots = [&] {
    const auto& times = scene.particleSnapshots;
    for (; nextSnapshot < times.size() && solver.time() >= times[nextSnapshot] - 0.5 * solver.timeStep(); ++nextSnapshot) {
      std::ostringstream name;
      name << "particles_t" << times[nextSnapshot] << ".csv";
      writeParticles(solver, dir / name.str());
    }
  };
  long checkpointStep = -1;  // the step of the checkpoint on disk
  auto lastCheckpoint = start;
  if (options.restart) {
    while (nextSnapshot < scene.particleSnapshots.size() &&
           solver.time() >= scene.particleSnapshots[nextSnapshot] - 0.5 * solver.timeStep())
      ++nextSnapshot;
    nextOutput = book.nextOutput;
    result.peakLoad = book.peakLoad;
    watch.peak = book.stopWatchPeak;
    checkpointStep = solver.step();
  }
  auto checkpoint = [&] {
    if (checkpointStep == solver.step()) return;
    history->flush();
    book.nextOutput = nextOutput;
    book.peakLoad = result.peakLoad;
    book.stopWatchPeak = watch.peak;
    book.history = {history->bytes(), history->digest(), history->rows()};
    if (snapshots) book.snapshotTimes = snapshots->times();
    writeCheckpoint(checkpointFile, solver, book, options.sceneHash);
    checkpointStep = solver.step();
    lastCheckpoint = Clock::now();
    ++result.checkpoints;
  };
  const CheckpointSettings& every = scene.checkpoint;
  auto stopRequested = [&] {
    return (options.stop && options.stop->load(std::memory_order_relaxed)) ||
           (options.maxSteps > 0 && solver.step() >= options.maxSteps);
  };

  bool outputFailed = false;
  try {
    if (!options.restart) {
      watchStop();
      output();
    }
    while (!finished()) {
      if (stopRequested()) {
        checkpoint();
        result.stopped = true;
        break;
      }
      solver.advance();
      trackPeak();
      particleSnapshots();
      if (finished() || (scene.outputInterval > 0.0 && solver.time() >= nextOutput - 0.5 * solver.timeStep())) {
        watchStop();
        output();
        while (scene.outputInterval > 0.0 && nextOutput <= solver.time() + 0.5 * solver.timeStep())
          nextOutput += scene.outputInterval;  // (output_interval 0: the last step only)
      }
      if (progress) progress->update(solver.time());
      if (!finished() && ((every.everySteps > 0 && solver.step() % every.everySteps == 0) ||
                          (every.everyMinutes > 0.0 && seconds(lastCheckpoint) >= 60.0 * every.everyMinutes)))
        checkpoint();
    }
    result.completed = !result.stopped;
  } catch (const SimulationError& e) {
    result.error = e.what();
    try {
      output(true);  // the state at the failure (history row and snapshot), for a look at what went wrong
    } catch (const io::OutputError& o) {
      result.error += std::string("; then: ") + o.what();
      outputFailed = true;
    }
  } catch (const io::OutputError& e) {
    // A file could not be written (full disk?): what is on disk stays readable (history.csv ends
    // with its last whole row, the other files are replaced atomically). Nothing more is written
    // but, if it can be, the summary.
    result.error = std::string(e.what()) + " (at step " + std::to_string(solver.step()) + ")";
    outputFailed = true;
  }
  if (progress) progress->finish();
  // What goes wrong from here on is added to the result; what was written stays readable.
  auto outputFailure = [&](const io::OutputError& o) {
    result.error = result.error.empty() ? o.what() : result.error + "; then: " + o.what();
    result.completed = result.stopped = false;
    outputFailed = true;
  };
  try {
    if (!outputFailed) history->close();
    if (!outputFailed) writeParticles(solver, dir / "particles_final.csv");  // also after a failure or a stop
  } catch (const io::OutputError& o) {
    outputFailure(o);
  }
  result.steps = solver.step();
  result.wallTime = seconds(start);
  std::error_code ec;
  if (result.completed) std::filesystem::remove(checkpointFile, ec);  // it describes an unfinished run
  if (std::filesystem::exists(checkpointFile, ec)) result.checkpoint = checkpointFile;

  const Energies e = solver.energies();
  const Particles& p = solver.particles();
  nlohmann::json summary = {
      {"scene", scene.name},
      {"status", result.completed ? "completed" : (result.stopped ? "stopped" : "failed")},
      {"peak_load", result.peakLoad},
      {"wall_time_s", result.wallTime},
      {"steps", result.steps},
      {"particles", result.particles},
      {"cracked_particles", p.bands.size()},
      {"bytes_per_particle_uncracked", p.bytesPerParticle()},
      {"bytes_per_particle_cracked", p.bytesPerParticle() + Particles::bytesPerBand()},
      {"time_step_s", solver.timeStep()},
      {"end_time_s", solver.time()},
      {"threads", solver.threads()},
      {"preset", scene.preset.empty() ? "none" : scene.preset},
      {"particles_per_cell", scene.particlesPerCell},
      {"cfl", scene.solver.cfl},
      {"scheme", toString(scene.solver.scheme)},
      {"shape_function", toString(scene.solver.shapeFunction)},
      {"substepped_updates", solver.substepped()},
      {"snap_back_releases", solver.snapBackReleases()},
      {"particle_updates_per_s",  // of this run's steps (after a restart: those since the checkpoint)
       result.wallTime > 0.0 ? static_cast<double>(result.particles) *
                                   static_cast<double>(result.steps - std::max(result.restartedFrom, 0L)) / result.wallTime
                             : 0.0},
      {"energies_Nmm",
       {{"kinetic", e.kinetic}, {"strain", e.strain}, {"external_work", e.externalWork}, {"dissipated", e.dissipated},
        {"damping", e.damping}}},
      {"checkpoints_written", result.checkpoints},
      {"units", "mm, N, MPa, t, s"}};
  if (scene.stopWhen) {
    const StopWhen& w = *scene.stopWhen;
    summary["stop_when"] = {{"condition", w.condition},
                            {"load_below", w.loadBelow},
                            {"after_time_s", w.afterTime},
                            {"met", result.endedByStopWhen},
                            {"peak_of_rows_N", watch.peak}};
    if (result.endedByStopWhen) summary["stop_when"]["load_at_stop_N"] = result.stopLoad;
  }
  if (!p.secondBand.empty()) {  // second_band: orthogonal (docs/model.md)
    summary["two_band_points"] = p.twoBandPoints();
    summary["bytes_per_particle_two_bands"] = p.bytesPerParticle() + 2 * Particles::bytesPerBand();
  }
  if (!result.completed && !result.stopped) summary["error"] = result.error;
  if (result.restartedFrom >= 0) summary["restarted_from_step"] = result.restartedFrom;
  if (!result.checkpoint.empty()) {
    summary["checkpoint"] = result.checkpoint.string();
    summary["checkpoint_step"] = checkpointStep;
  }
  if (result.stopped && !options.resumeCommand.empty()) summary["resume"] = options.resumeCommand;
  try {
    io::writeJsonSummary(summary, dir / "summary.json");
  } catch (const io::OutputError& o) {  // the old summary, if any, stays whole
    outputFailure(o);
  }
  if (!outputFailed && options.plot && !result.stopped) {
    plot(scene, dir);
    plotDamage(scene, solver.particles().size(), dir);
  }
  return result;
}

}  // namespace ecm::mpm
