// ns per 3D constitutive update (material/two_phase_point_3d.hpp), next to the 2D ones of
// material_bench.cpp on the same paths embedded in 3D. Target: <= 2x the 2D update, intact and
// softening (docs/performance.md).
#include <benchmark/benchmark.h>

#include <optional>
#include <vector>

#include "bench/intact_updates.hpp"
#include "material/material_3d.hpp"

namespace {

using namespace ecm;

EnrichedParams concrete3() { return {{{32000.0, 0.2, Hypothesis::ThreeDimensional}, 3.0, 8.184, 0.128}, 0.05}; }
Voigt6 embed(double xx, double yy, double zz, double xy) { return (Voigt6() << xx, yy, zz, 0.0, 0.0, xy).finished(); }
const Voigt6 kStep3 = embed(2e-7, -2e-8, -2e-8, 3e-8);
constexpr int kBatch = 1024;

void BM_Enriched3DIntact(benchmark::State& st) {
  std::vector<Voigt6> strains(kBatch);
  for (int i = 0; i < kBatch; ++i) strains[i] = embed(2e-5 + 1e-8 * i, -1e-6, -1e-6, 1e-7 * (i % 7));
  intactUpdates(st, TwoPhasePoint3D(concrete3()), strains, kStep3, EffectiveSize3::fixed(2.5));
}
BENCHMARK(BM_Enriched3DIntact);

// The 2D benchmark's cracked point (40 increments in tension and shear) in 3D.
void BM_Enriched3DCrackedSoftening(benchmark::State& st) {
  const TwoPhasePoint3D model(concrete3());
  const auto size = EffectiveSize3::fixed(2.5);
  Voigt6 strain = Voigt6::Zero();
  std::optional<BandState3> band;
  for (int i = 0; i < 40; ++i) {
    const Voigt6 d = embed(5e-6, -1e-6, -1e-6, 1e-6);
    if (band) model.updateCracked(*band, strain, d, SnapBackPolicy::Stop);
    else model.updateIntact(strain, d, size, band, SnapBackPolicy::Stop);
  }
  if (!band) return st.SkipWithError("point did not crack");
  const UpdateOptions options{SnapBackPolicy::Stop, st.range(0) != 0};
  for (auto _ : st) {
    BandState3 b = *band;
    Voigt6 s = strain;
    const UpdateResult3 r = model.updateCracked(b, s, kStep3, options);
    benchmark::DoNotOptimize(r);
  }
  BandState3 b = *band;
  Voigt6 s = strain;
  const UpdateResult3 r = model.updateCracked(b, s, kStep3, options);
  st.counters["newton_iterations"] = r.iterations;
  st.counters["damage"] = band->damage();
  if (!(b.integrity < band->integrity)) st.SkipWithError("the band did not load");
}
BENCHMARK(BM_Enriched3DCrackedSoftening)->Arg(1)->Arg(0)->ArgName("tangent");

}  // namespace
