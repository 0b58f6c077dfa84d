// Calibration speed: one E_p solve from G_F and one Hordijk fit of (E_p, n), both for the paper's
// DEN concrete (E = 32000 MPa, f_t' = 3 MPa, G_F = 0.11 N/mm, h = 0.05 mm). Target: < 50 ms each.
#include <benchmark/benchmark.h>

#include "calibration/fracture_energy.hpp"
#include "calibration/softening_fit.hpp"

namespace {

constexpr double kE = 32000.0, kFt = 3.0, kGF = 0.11, kH = 0.05, kN = 0.128;

void SolveSofteningModulus(benchmark::State& state) {
  for (auto _ : state) {
    const auto s = ecm::calibration::solveSofteningModulus({kE, kFt, 0.0, kN}, kGF, kH);
    benchmark::DoNotOptimize(s.softeningModulus);
  }
  state.SetLabel("E_p for n = 0.128 (paper concrete)");
}
BENCHMARK(SolveSofteningModulus)->Unit(benchmark::kMillisecond);

void HordijkFit(benchmark::State& state) {
  const ecm::calibration::TargetCurve target = ecm::calibration::hordijkCurve(kFt, kGF);
  int evaluations = 0;
  for (auto _ : state) {
    const auto f = ecm::calibration::fitSoftening({kE, kFt, 0.0, 0.0}, kGF, kH, target);
    benchmark::DoNotOptimize(f.softeningExponent);
    evaluations = f.evaluations;
  }
  state.counters["evaluations"] = evaluations;
  state.SetLabel("(E_p, n) to 100 Hordijk points at fixed G_F");
}
BENCHMARK(HordijkFit)->Unit(benchmark::kMillisecond);

}  // namespace
