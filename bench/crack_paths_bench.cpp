// What tracked crack paths cost an explicit run (docs/model.md, "Crack paths"): the notched beam
// of data/validation/beam-coarse.yaml (5,560 particles, 2.5 mm cells), loaded ten times faster
// than the scene (12 mm/s: the cost, not the curve), with `crack_path: free` and `tracked`.
//   stage 0: the first 500 steps, every point intact: tracking must cost nothing there;
//   stage 1: 500 steps from t = 9 ms, the crack growing up the ligament (the point updates of the
//            cracked and held points, the paths' growth and their per-cell lookups).
// Reported: particle-updates per second (particles x steps / wall time) and the cracked points.
// Set-up and the run to the stage are not timed. Run: ./build/bench/bench_crack_paths
#include <benchmark/benchmark.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <unistd.h>

#include "mpm/explicit/explicit_solver.hpp"
#include "mpm/scene/scene_yaml.hpp"

namespace {

using namespace ecm::mpm;

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  if (at == std::string::npos) throw std::runtime_error("bench_crack_paths: the beam scene has no '" + from + "'");
  return text.replace(at, from.size(), to);
}

// The beam scene, ten times faster, with the given rule (written to a temporary file: the scene
// reader takes files, and its material path is made absolute).
Scene beam(bool tracked) {
  std::ifstream in(ECM_SOURCE_DIR "/data/validation/beam-coarse.yaml");
  std::stringstream s;
  s << in.rdbuf();
  std::string text = s.str();
  text = replaced(text, "{file: ../materials/", "{file: " ECM_SOURCE_DIR "/data/materials/");
  text = replaced(text, "end_time: 0.5 ", "end_time: 0.05 ");
  text = replaced(text, "value: -0.6, time: 0.5}", "value: -0.6, time: 0.05}");
  text = replaced(text, "crack_path: tracked", tracked ? "crack_path: tracked" : "crack_path: free");
  const std::filesystem::path file =
      std::filesystem::temp_directory_path() / ("ecm-bench-beam-" + std::to_string(::getpid()) + ".yaml");
  std::ofstream(file) << text;
  Scene scene = loadSceneFile(file);
  std::filesystem::remove(file);
  return scene;
}

void BM_BeamStep(benchmark::State& state) {
  const bool tracked = state.range(0) != 0;
  const bool growing = state.range(1) != 0;
  ExplicitSolver solver(beam(tracked), 1);
  if (growing)
    while (solver.time() < 9e-3) solver.advance();
  constexpr int kSteps = 500;
  for (auto _ : state) {
    state.PauseTiming();
    ExplicitSolver run = solver;  // each iteration times the same 500 steps
    state.ResumeTiming();
    for (int n = 0; n < kSteps; ++n) run.advance();
    state.counters["cracked"] = static_cast<double>(run.particles().bands.size());
  }
  const double particles = static_cast<double>(solver.particles().size());
  state.counters["particle_updates_per_s"] =
      benchmark::Counter(particles * kSteps * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.SetLabel(std::string(tracked ? "tracked" : "free") + (growing ? ", crack growing" : ", intact"));
}
BENCHMARK(BM_BeamStep)
    ->ArgsProduct({{0, 1}, {0, 1}})
    ->ArgNames({"tracked", "growing"})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace
