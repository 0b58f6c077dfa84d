// The two-disks benchmark (data/mpm/two-disks.yaml): two elastic disks of ~50,200 particles
// each, 316 x 316 cells, linear shape functions, MUSL, pure FLIP, dt = 0.2 x cell; 500 steps
// (before contact) and 3200 steps (through contact), kinetic and strain energy every 100 steps.
// usl:1 runs its USL variant (data/mpm/two-disks-usl.yaml) for 500 steps.
// Reported: particle-updates per second = particles x steps / (wall time - set-up time), per
// core (divided by the threads), on 1 and 2 threads; bytes per particle of the solver (particle
// arrays, scatter order and grid fields) and the process's peak RSS per particle (an
// upper bound: the whole benchmark process). Set-up (reading the scene, seeding) is not timed.
// Run: scripts/two-disks.sh, or ./build/bench/bench_two_disks
#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include "mpm/scene/scene_yaml.hpp"
#include "mpm/explicit/explicit_solver.hpp"

namespace {

using namespace ecm::mpm;

// scheme 0: the benchmark as published (MUSL); 1: its USL variant (data/mpm/two-disks-usl.yaml).
const Scene& twoDisks(int scheme) {
  static const Scene musl = loadSceneFile(ECM_SOURCE_DIR "/data/mpm/two-disks.yaml");
  static const Scene usl = loadSceneFile(ECM_SOURCE_DIR "/data/mpm/two-disks-usl.yaml");
  return scheme == 0 ? musl : usl;
}

// Bytes of the solver's arrays per particle: the particle fields, its slot in the scatter order
// and the grid fields (no per-thread copy of the grid: mpm/explicit/scatter_order.hpp).
double solverBytesPerParticle(const ExplicitSolver& s) {
  const double particles = static_cast<double>(s.particles().size());
  const GridFields& g = s.grid();
  const double nodes = static_cast<double>(g.mass.size());
  const double grid = nodes * (sizeof(double) + 5.0 * sizeof(ecm::Vec2));
  return static_cast<double>(s.particles().bytesPerParticle() + sizeof(std::uint32_t)) + grid / particles;
}

void BM_TwoDisks(benchmark::State& state) {
  const int threads = static_cast<int>(state.range(0));
  const long steps = state.range(1);
  const int scheme = static_cast<int>(state.range(2));
  double particles = 0.0, bytes = 0.0, kinetic = 0.0, strain = 0.0;
  for (auto _ : state) {
    state.PauseTiming();
    ExplicitSolver solver(twoDisks(scheme), threads);
    state.ResumeTiming();
    for (long n = 1; n <= steps; ++n) {
      solver.advance();
      if (n % 100 == 0) {  // the benchmark's energy line
        const Energies e = solver.energies();
        benchmark::DoNotOptimize(e);  // read-only: DoNotOptimize(double&) clobbers doubles with this GCC
        kinetic = e.kinetic;
        strain = e.strain;
      }
    }
    particles = static_cast<double>(solver.particles().size());
    bytes = solverBytesPerParticle(solver);
  }
  struct rusage usage {};
  ::getrusage(RUSAGE_SELF, &usage);
  const double updates = particles * static_cast<double>(steps) * static_cast<double>(state.iterations());
  state.counters["particles"] = particles;
  state.counters["updates_per_s"] = benchmark::Counter(updates, benchmark::Counter::kIsRate);
  state.counters["updates_per_s_per_core"] = benchmark::Counter(updates / threads, benchmark::Counter::kIsRate);
  state.counters["solver_bytes_per_particle"] = bytes;
  state.counters["peak_rss_bytes_per_particle"] = static_cast<double>(usage.ru_maxrss) * 1024.0 / particles;
  state.counters["kinetic_end"] = kinetic;
  state.counters["strain_end"] = strain;
}
BENCHMARK(BM_TwoDisks)
    ->ArgsProduct({{1, 2}, {500}, {0, 1}})
    ->ArgNames({"threads", "steps", "usl"})
    ->Iterations(2)
    ->UseRealTime()
    ->Unit(benchmark::kSecond);
BENCHMARK(BM_TwoDisks)
    ->ArgsProduct({{1, 2}, {3200}, {0}})
    ->ArgNames({"threads", "steps", "usl"})
    ->Iterations(1)
    ->UseRealTime()
    ->Unit(benchmark::kSecond);

}  // namespace
