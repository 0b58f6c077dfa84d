// MPM throughput: particle-updates per second (particles x steps / wall time) for one full
// explicit step (P2G, grid update, G2P, stress update), on 1 and 2 threads, and the same step
// phase by phase (BM_Phase: only the named phase timed; output = one VTU snapshot).
// Targets: >= 20 M elastic particle-updates/s per core with linear shape functions,
// >= 1.8x on 2 threads, <= 300 bytes per uncracked particle.
#include <benchmark/benchmark.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <unistd.h>

#include "mpm/explicit/explicit_solver.hpp"
#include "mpm/output/vtu_writer.hpp"

namespace {

using namespace ecm;
using namespace ecm::mpm;

MaterialParams elastic() {
  MaterialParams m{.name = "elastic", .model = ModelKind::LinearElastic,
                   .elastic = {32000.0, 0.2, Hypothesis::PlaneStress}, .density = 2.4e-9};
  return m;
}

MaterialParams concrete() {
  MaterialParams m = elastic();
  m.name = "den-concrete";
  m.model = ModelKind::Enriched;
  m.tensileStrength = 3.0;
  m.softeningModulus = 8.184;
  m.softeningExponent = 0.128;
  m.bandWidth = 0.05;
  return m;
}

// cells x cells block with 2 x 2 particles per cell (plus a margin of 2 cells), 1 mm cells.
Scene block(int cells, const MaterialParams& m, ShapeFunction shape) {
  Scene s;
  s.grid = {Vec2::Zero(), Vec2(1.0, 1.0), cells + 4, cells + 4};
  s.materials = {m};
  s.bodies = {{Shape::rectangle(Vec2(2.0, 2.0), Vec2(cells + 2.0, cells + 2.0)), 0, false, Vec2::Zero()}};
  s.solver.shapeFunction = shape;
  s.solver.crackPath = CrackPathRule::Free;  // every point of a stretched block cracks where it stands
  return s;
}

void report(benchmark::State& state, const ExplicitSolver& solver) {
  const double n = static_cast<double>(solver.particles().size());
  state.counters["particles"] = n;
  state.counters["particle_updates_per_s"] =
      benchmark::Counter(n * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["bytes_per_particle"] = static_cast<double>(solver.particles().bytesPerParticle());
  state.counters["bytes_per_cracked"] =
      static_cast<double>(solver.particles().bytesPerParticle() + solver.particles().bytesPerBand());
}

// ~100k elastic particles vibrating freely (an initial velocity field).
void BM_ElasticStep(benchmark::State& state) {
  const auto shape = static_cast<ShapeFunction>(state.range(1));
  ExplicitSolver solver(block(158, elastic(), shape), static_cast<int>(state.range(0)));
  auto& p = solver.editParticles();
  for (std::size_t i = 0; i < p.size(); ++i)
    p.velocity[i] = Vec2(100.0 * std::sin(0.05 * p.position[i][1]), 50.0 * std::cos(0.03 * p.position[i][0]));
  for (auto _ : state) solver.advance();
  report(state, solver);
}
BENCHMARK(BM_ElasticStep)
    ->ArgsProduct({{1, 2}, {static_cast<int>(ShapeFunction::Linear)}})
    ->ArgsProduct({{1}, {static_cast<int>(ShapeFunction::UGimp), static_cast<int>(ShapeFunction::BSpline2)}})
    ->ArgNames({"threads", "shape"})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

// Every particle cracked and softening: the block is driven by an affine velocity field
// (all grid nodes prescribed) until all points have cracked, then timed.
// The concrete block of 70 x 70 cells driven by an affine velocity field on every grid node.
Scene stretchedBlock() {
  Scene s = block(70, concrete(), ShapeFunction::Linear);
  NodeCondition all;
  all.name = "all";
  all.box = {Vec2(-1.0, -1.0), Vec2(1e3, 1e3)};
  Mat2 g;
  g << 1.0, 0.2, 0.0, -0.1;
  all.field = AffineVelocity{400.0 * g, Vec2(37.0, 37.0), TimeFunction::hold(1.0)};
  s.conditions = {all};
  return s;
}

void BM_CrackedStep(benchmark::State& state) {
  const Scene s = stretchedBlock();
  ExplicitSolver solver(s, static_cast<int>(state.range(0)));
  while (solver.particles().bands.size() < solver.particles().size()) solver.advance();
  for (auto _ : state) solver.advance();
  report(state, solver);
}
BENCHMARK(BM_CrackedStep)->Arg(1)->Arg(2)->ArgName("threads")->UseRealTime()->Unit(benchmark::kMillisecond);

// The USL step phase by phase: P2G (stencils, mass, momentum, forces), grid update (with
// conditions), G2P (velocities, positions, strain increments), stress update, and output (one
// VTU snapshot of all particles; a run writes one every output_interval, e.g. every 75 steps on
// the DEN coarse scene). Only the named phase is timed; the step runs whole, so the state
// evolves as in a run. Elastic: the 100k-particle block of BM_ElasticStep; cracked: the block of
// BM_CrackedStep with every point cracked and softening.
enum Phase : int { kP2G, kGrid, kG2P, kStress, kOutput };
const char* const kPhaseNames[] = {"p2g", "grid", "g2p", "stress", "output"};

void BM_Phase(benchmark::State& state) {
  const auto phase = static_cast<Phase>(state.range(0));
  const bool cracked = state.range(1) != 0;
  const int threads = static_cast<int>(state.range(2));
  const Scene s = cracked ? stretchedBlock() : block(158, elastic(), ShapeFunction::Linear);
  ExplicitSolver solver(s, threads);
  auto& p = solver.editParticles();
  if (cracked) {
    while (p.bands.size() < p.size()) solver.advance();
  } else {
    for (std::size_t i = 0; i < p.size(); ++i)
      p.velocity[i] = Vec2(100.0 * std::sin(0.05 * p.position[i][1]), 50.0 * std::cos(0.03 * p.position[i][0]));
  }
  const std::filesystem::path vtu =
      std::filesystem::temp_directory_path() / ("ecm-bench-phase-" + std::to_string(::getpid()) + ".vtu");
  std::string scratch;  // kept between snapshots, as VtuSeries does in a run
  const auto timed = [&](Phase ph, auto&& run) {
    if (ph != phase) state.PauseTiming();
    run();
    if (ph != phase) state.ResumeTiming();
  };
  const StepSetup& setup = solver.setup();
  MpmState& st = solver.editState();  // the plain USL phases of mpm/explicit/step.cpp, run by hand
  for (auto _ : state) {
    timed(kP2G, [&] {
      particleToGrid(setup, st.clock.step, st.particles, st.grid, st.order, kStencils | kMassMomentum | kForces);
      addLoads(setup, st.clock.time, st.particles, st.grid, st.loads);
    });
    timed(kGrid, [&] { updateGrid(setup, st.clock, st.grid, st.conditions, st.totals); });
    timed(kG2P, [&] { gridToParticle(setup, st.clock, st.grid, st.particles, true); });
    timed(kStress, [&] { updateStresses(setup, st.clock.step, st.particles, st.totals, st.crackPaths); });
    timed(kOutput, [&] { writeVtu(solver.particles(), solver.time(), vtu, &scratch); });
  }
  std::filesystem::remove(vtu);
  state.SetLabel(std::string(kPhaseNames[phase]) + (cracked ? ", cracked" : ", elastic"));
  report(state, solver);
}
BENCHMARK(BM_Phase)
    ->ArgsProduct({{kP2G, kGrid, kG2P, kStress, kOutput}, {0}, {1, 2}})
    ->ArgNames({"phase", "cracked", "threads"})
    ->UseRealTime()
    ->Unit(benchmark::kMicrosecond);
// The cracked block keeps stretching in its velocity field: a fixed number of steps keeps it
// inside the grid (a few hundred steps would carry its edge particles out).
BENCHMARK(BM_Phase)
    ->ArgsProduct({{kP2G, kGrid, kG2P, kStress, kOutput}, {1}, {1, 2}})
    ->ArgNames({"phase", "cracked", "threads"})
    ->Iterations(40)
    ->UseRealTime()
    ->Unit(benchmark::kMicrosecond);

}  // namespace
