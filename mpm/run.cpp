#include "mpm/run.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <nlohmann/json.hpp>

#include "io/csv_writer.hpp"
#include "io/gnuplot.hpp"
#include "io/json_summary.hpp"
#include "io/output_dir.hpp"
#include "io/progress.hpp"
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

// The final state of every particle (x, y, damage, material id, normal opening of the band), for
// damage and crack maps.
void writeParticles(const Solver& s, const std::filesystem::path& path) {
  io::CsvWriter csv(path, {"x_mm", "y_mm", "damage", "material", "opening_mm"});
  const Particles& p = s.particles();
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double opening = p.band[i] >= 0 ? p.bands[static_cast<std::size_t>(p.band[i])].normalJump() : 0.0;
    csv.row({p.position[i][0], p.position[i][1], s.damage(i), static_cast<double>(p.material[i]), opening});
  }
  csv.close();
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
  const auto start = std::chrono::steady_clock::now();
  auto seconds = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  Solver solver(scene, options.threads);  // throws on an invalid scene, before any output
  const std::filesystem::path dir = io::prepareOutputDir(options.outputDir);

  io::CsvWriter history(dir / "history.csv", historyColumns(scene));
  std::unique_ptr<VtuSeries> snapshots;
  if (options.snapshots) snapshots = std::make_unique<VtuSeries>(dir);
  std::unique_ptr<io::Progress> progress;
  if (options.progress) {
    io::Progress::Options o;
    o.label = "ecm-mpm " + scene.name;
    progress = std::make_unique<io::Progress>(scene.endTime, o);
  }

  RunResult result;
  result.particles = solver.particles().size();
  auto output = [&] {
    history.row(historyRow(solver));
    history.flush();
    if (snapshots) snapshots->add(solver);
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

  output();
  double nextOutput = scene.outputInterval;
  try {
    // A half-step tolerance so that round-off in the accumulated time does not add a step.
    while (solver.time() < scene.endTime - 0.5 * solver.timeStep()) {
      solver.advance();
      trackPeak();
      const bool last = solver.time() >= scene.endTime - 0.5 * solver.timeStep();
      if (last || (scene.outputInterval > 0.0 && solver.time() >= nextOutput - 0.5 * solver.timeStep())) {
        output();
        while (nextOutput <= solver.time() + 0.5 * solver.timeStep()) nextOutput += scene.outputInterval;
      }
      if (progress) progress->update(solver.time());
    }
    result.completed = true;
  } catch (const SimulationError& e) {
    result.error = e.what();
    output();  // the state at the failure, for a look at what went wrong
  }
  if (progress) progress->finish();
  history.close();
  result.steps = solver.step();
  result.wallTime = seconds();

  const Energies e = solver.energies();
  const Particles& p = solver.particles();
  nlohmann::json summary = {
      {"scene", scene.name},
      {"status", result.completed ? "completed" : "failed"},
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
      {"scheme", toString(scene.solver.scheme)},
      {"shape_function", toString(scene.solver.shapeFunction)},
      {"substepped_updates", solver.substepped()},
      {"snap_back_releases", solver.snapBackReleases()},
      {"particle_updates_per_s", result.wallTime > 0.0 ? static_cast<double>(result.particles) * result.steps / result.wallTime : 0.0},
      {"energies_Nmm",
       {{"kinetic", e.kinetic}, {"strain", e.strain}, {"external_work", e.externalWork}, {"dissipated", e.dissipated},
        {"damping", e.damping}}},
      {"units", "mm, N, MPa, t, s"}};
  if (!result.completed) summary["error"] = result.error;
  writeParticles(solver, dir / "particles_final.csv");  // also after a failure: the state at it
  io::writeJsonSummary(summary, dir / "summary.json");
  if (options.plot) {
    plot(scene, dir);
    plotDamage(scene, solver.particles().size(), dir);
  }
  return result;
}

}  // namespace ecm::mpm
