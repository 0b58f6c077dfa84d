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
#include "mpm/implicit_solver.hpp"

namespace ecm::mpm {

namespace {

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

}  // namespace

RunResult runImplicitScene(const Scene& scene, const RunOptions& options) {
  if (options.restart) throw std::invalid_argument("implicit_static runs have no checkpoints yet: there is nothing to restart");
  const auto start = std::chrono::steady_clock::now();
  const ImplicitSettings& settings = *scene.solver.implicit;
  io::prepareOutputDir(options.outputDir);
  ImplicitSolver solver(scene, options.threads,
                        {settings.tolerance, settings.maxIterations, settings.maxHalvings,
                         settings.umfpack ? LinearSolverKind::Umfpack : LinearSolverKind::SparseLU});
  RunResult result;
  result.particles = solver.particles().size();

  std::vector<std::string> columns = historyColumns(scene);
  for (const char* c : {"load_factor", "newton_iterations", "halvings", "snapback_releases", "load_step", "onset_overshoot",
                        "internal_work_Nmm", "work_dissipated_Nmm"})
    columns.emplace_back(c);
  io::CsvWriter history(options.outputDir / "history.csv", columns);
  long iterations = 0, halvings = 0, released = 0, factorizations = 0;
  int mostIterations = 0;
  double linearSolve = 0.0;
  const auto row = [&](const ImplicitStepReport& r) {
    std::vector<double> v{solver.time(), static_cast<double>(solver.steps())};
    for (const ConditionState& c : solver.conditions()) v.insert(v.end(), {c.displacement[0], c.displacement[1], c.reaction[0], c.reaction[1]});
    for (const Load& l : scene.loads) {
      const Vec2 f = l.force * l.history(solver.time());
      v.insert(v.end(), {f[0], f[1]});
    }
    const Energies e = solver.energies();
    long cracked = 0;
    for (const auto b : solver.particles().band) cracked += b >= 0 ? 1 : 0;
    v.insert(v.end(), {0.0, e.strain, e.externalWork, e.dissipated, 0.0, static_cast<double>(cracked), solver.loadFactor(),
                       static_cast<double>(r.totalIterations), static_cast<double>(r.cuts), static_cast<double>(r.released), r.size,
                       r.onsetOvershoot, solver.internalWork(), solver.internalWork() - e.strain});
    history.row(v);
    history.flush();
  };
  // The peak of the driven conditions' reactions (all conditions' if none is driven) and loads, as
  // explicit runs report it.
  bool anyDriven = false;
  for (const NodeCondition& c : scene.conditions) anyDriven = anyDriven || isDriven(c);
  const auto trackPeak = [&] {
    for (std::size_t i = 0; i < scene.conditions.size(); ++i)
      if (isDriven(scene.conditions[i]) || !anyDriven)
        result.peakLoad = std::max(result.peakLoad, solver.conditions()[i].reaction.norm());
    for (const Load& l : scene.loads) result.peakLoad = std::max(result.peakLoad, (l.force * l.history(solver.time())).norm());
  };
  std::unique_ptr<io::Progress> progress;
  const double total = settings.indirect ? settings.indirect->until : scene.endTime;
  if (options.progress) {
    io::Progress::Options o;
    o.label = "ecm-mpm " + scene.name + " (implicit)";
    progress = std::make_unique<io::Progress>(total, o);
  }
  row({});
  try {
    double done = 0.0;
    const IndirectControl control = settings.indirect ? indirectControl(scene) : IndirectControl{};
    const double largest = settings.indirect ? settings.indirect->step : settings.loadStep;
    while (done < total * (1.0 - 1e-12)) {
      const ImplicitStepReport r = settings.indirect ? solver.advance(control, largest, total - done)
                                                     : solver.advance(largest, total - done);
      done += r.size;
      iterations += r.totalIterations, halvings += r.cuts, released += r.released;
      mostIterations = std::max(mostIterations, r.totalIterations);
      linearSolve += r.linearSolveSeconds;
      factorizations += r.factorizations;
      trackPeak();
      row(r);
      if (progress) progress->update(done);
      if ((options.onRow && !options.onRow(solver.time(), solver.steps())) ||
          (options.stop && options.stop->load()) || (options.maxSteps > 0 && solver.steps() >= options.maxSteps)) {
        result.error = "stopped on request at step " + std::to_string(solver.steps()) +
                       " (implicit_static runs have no checkpoints yet: the outputs so far are kept)";
        break;
      }
    }
    result.completed = result.error.empty();
  } catch (const SimulationError& e) {
    result.error = e.what();
  } catch (const io::OutputError& e) {
    result.error = e.what();
  }
  if (progress) progress->finish();
  history.close();
  result.steps = solver.steps();
  result.wallTime = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  writeParticles(solver.particles(), options.outputDir / "particles_final.csv");
  long cracked = 0;
  for (const auto b : solver.particles().band) cracked += b >= 0 ? 1 : 0;
  nlohmann::json j;
  j["units"] = "mm, N, MPa, t, s (time: pseudo-time)";
  j["scene"] = scene.name;
  j["scheme"] = "implicit_static";
  j["control"] = settings.indirect ? "indirect" : "displacement";
  j["status"] = result.completed ? "completed" : "failed";
  if (!result.completed) j["error"] = result.error;
  j["steps"] = result.steps;
  j["particles"] = result.particles;
  j["peak_load_N"] = result.peakLoad;
  j["load_factor"] = solver.loadFactor();
  j["newton_iterations"] = iterations;
  j["newton_iterations_per_step"] = result.steps > 0 ? static_cast<double>(iterations) / static_cast<double>(result.steps) : 0.0;
  j["most_newton_iterations_in_a_step"] = mostIterations;
  j["halvings"] = halvings;
  j["linear_solve_s"] = linearSolve;
  j["factorizations"] = factorizations;
  j["linear_solver"] = settings.umfpack ? "umfpack" : "sparselu";
  j["snap_back_releases"] = released;
  j["cracked_particles"] = cracked;
  const Energies e = solver.energies();
  // Two dissipations (docs/implicit.md, "Energies"): the model's f int Y dD, and the internal work
  // minus the strain energy, which the external work balances step by step.
  j["energies_Nmm"] = {{"strain", e.strain},
                       {"external_work", e.externalWork},
                       {"internal_work", solver.internalWork()},
                       {"dissipated", e.dissipated},
                       {"work_dissipated", solver.internalWork() - e.strain}};
  j["energy_balance"] = std::abs(e.externalWork - solver.internalWork()) / std::max(std::abs(e.externalWork), 1e-300);
  j["wall_time_s"] = result.wallTime;
  j["threads"] = solver.setup().threads;
  io::writeJsonSummary(j, options.outputDir / "summary.json");
  if (options.plot) {
    plotLoadDisplacement(scene, options.outputDir);
    plotDamage(scene, solver.particles().size(), options.outputDir);
  }
  return result;
}

}  // namespace ecm::mpm
