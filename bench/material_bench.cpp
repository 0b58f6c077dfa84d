// ns per constitutive update. Targets: uncracked enriched within 1.5x of elastic;
// cracked enriched in softening <= 1 microsecond.
#include <benchmark/benchmark.h>

#include <optional>
#include <vector>

#include "bench/intact_updates.hpp"
#include "material/material.hpp"

namespace {

using namespace ecm;

EnrichedParams concrete() { return {{{32000.0, 0.2, Hypothesis::PlaneStress}, 3.0, 8.184, 0.128}, 0.05}; }
const Voigt kStep(2e-7, -2e-8, 3e-8);

// Intact points are updated in batches, as a solver sweeps its particles: time per update.
constexpr int kBatch = 1024;

std::vector<Voigt> batchStrains() {
  std::vector<Voigt> strains(kBatch);
  for (int i = 0; i < kBatch; ++i) strains[i] = Voigt(2e-5 + 1e-8 * i, -1e-6, 1e-7 * (i % 7));
  return strains;
}

void BM_Elastic(benchmark::State& st) {
  const LinearElastic model({32000.0, 0.2, Hypothesis::PlaneStress});
  std::vector<LinearElastic::State> points;
  for (const Voigt& e : batchStrains()) points.push_back({e});
  for (auto _ : st) {
    for (auto& p : points) {
      const UpdateResult r = model.update(p, kStep);
      benchmark::DoNotOptimize(r.stress);
      p.strain -= kStep;  // stay in place, elastic
    }
  }
  st.SetItemsProcessed(st.iterations() * kBatch);
}
BENCHMARK(BM_Elastic);

void BM_EnrichedIntact(benchmark::State& st) {
  intactUpdates(st, TwoPhasePoint(concrete()), batchStrains(), kStep, EffectiveSize::fixed(2.5));
}
BENCHMARK(BM_EnrichedIntact);

// A point driven 40 increments past onset in tension and shear (D ~ 0.98).
EnrichedState crackedPoint(const TwoPhasePoint& model, const EffectiveSize& size) {
  EnrichedState s;
  for (int i = 0; i < 40; ++i) model.update(s, Voigt(5e-6, -1e-6, 1e-6), size);
  return s;
}

// Times updateCracked of `s` by `increment`, from the same state each time; range(0): tangent.
void timeCrackedUpdate(benchmark::State& st, const TwoPhasePoint& model, const EnrichedState& s, const Voigt& increment) {
  if (!s.band) return st.SkipWithError("point did not crack");
  const UpdateOptions options{SnapBackPolicy::Stop, st.range(0) != 0};
  for (auto _ : st) {
    BandState band = *s.band;
    Voigt strain = s.strain;
    const UpdateResult r = model.updateCracked(band, strain, increment, options);
    benchmark::DoNotOptimize(r);
  }
}

void BM_EnrichedCrackedSoftening(benchmark::State& st) {
  const TwoPhasePoint model(concrete());
  const auto size = EffectiveSize::fixed(2.5);
  const EnrichedState s = crackedPoint(model, size);
  timeCrackedUpdate(st, model, s, kStep);
  if (!s.band) return;
  EnrichedState copy = s;
  st.counters["newton_iterations"] = model.update(copy, kStep, size).iterations;
  st.counters["damage"] = s.band->damage();
}
// Arg tangent: 1 with the consistent tangent (implicit callers, the point driver), 0 without (explicit MPM).
BENCHMARK(BM_EnrichedCrackedSoftening)->Arg(1)->Arg(0)->ArgName("tangent");

// A cracked point whose band unloads (the elastic predictor is the answer): in the DEN runs
// about 80 % of the cracked updates are of this kind (counted on the coarse mesh).
void BM_EnrichedCrackedUnloading(benchmark::State& st) {
  const TwoPhasePoint model(concrete());
  const auto size = EffectiveSize::fixed(2.5);
  const EnrichedState s = crackedPoint(model, size);
  timeCrackedUpdate(st, model, s, -kStep);
  if (!s.band) return;
  EnrichedState copy = s;
  model.update(copy, -kStep, size);
  if (copy.band->integrity != s.band->integrity) st.SkipWithError("the band loaded");
}
BENCHMARK(BM_EnrichedCrackedUnloading)->Arg(1)->Arg(0)->ArgName("tangent");

// The second-band option (docs/model.md, "A second band"). A one-band point with the option on
// pays for the trigger check: the bulk stress along its band's tangent.
void BM_EnrichedCrackedSofteningOptionOn(benchmark::State& st) {
  EnrichedParams p = concrete();
  p.secondBand = SecondBandOption::Orthogonal;
  const TwoPhasePoint model(p);
  const auto size = EffectiveSize::fixed(2.5);
  const EnrichedState s = crackedPoint(model, size);
  if (!s.band || s.secondBand) return st.SkipWithError("expected one band");
  const UpdateOptions options{SnapBackPolicy::Stop, st.range(0) != 0};
  for (auto _ : st) {
    BandState band = *s.band;
    Voigt strain = s.strain;
    std::optional<BandState> opened;
    const UpdateResult r = model.updateCracked(band, nullptr, strain, kStep, size, opened, options);
    benchmark::DoNotOptimize(r);
  }
}
BENCHMARK(BM_EnrichedCrackedSofteningOptionOn)->Arg(1)->Arg(0)->ArgName("tangent");

// A point with two softened bands: a nearly equibiaxial stretch (both damages above 0.3).
EnrichedState twoBandPoint(const TwoPhasePoint& model, const EffectiveSize& size) {
  EnrichedState s;
  for (int i = 0; i < 400 && !(s.secondBand && s.secondBand->damage() > 0.3); ++i)
    model.update(s, Voigt(2e-6, 2e-6, 1e-7), size);
  return s;
}

// Times updateTwoBands from the same state each time, the increment along the bands' normals
// (sign +1: both load, -1: both unload); range(0): tangent.
void timeTwoBands(benchmark::State& st, double sign) {
  EnrichedParams p = concrete();
  p.secondBand = SecondBandOption::Orthogonal;
  const TwoPhasePoint model(p);
  const EnrichedState s = twoBandPoint(model, EffectiveSize::fixed(10.0));
  if (!s.secondBand) return st.SkipWithError("no second band");
  const auto dyad = [](const Vec2& n) { return Voigt(n[0] * n[0], n[1] * n[1], 2.0 * n[0] * n[1]); };
  const Voigt increment = sign * 2e-7 * (dyad(s.band->crackNormal) + dyad(s.secondBand->crackNormal));
  const UpdateOptions options{SnapBackPolicy::Stop, st.range(0) != 0};
  int iterations = 0;
  for (auto _ : st) {
    BandState first = *s.band, second = *s.secondBand;
    Voigt strain = s.strain;
    const UpdateResult r = model.updateTwoBands(first, second, strain, increment, options);
    iterations = r.iterations;
    benchmark::DoNotOptimize(r);
  }
  st.counters["newton_iterations"] = iterations;
}
void BM_EnrichedTwoBandsSoftening(benchmark::State& st) { timeTwoBands(st, 1.0); }
void BM_EnrichedTwoBandsUnloading(benchmark::State& st) { timeTwoBands(st, -1.0); }
BENCHMARK(BM_EnrichedTwoBandsSoftening)->Arg(1)->Arg(0)->ArgName("tangent");
BENCHMARK(BM_EnrichedTwoBandsUnloading)->Arg(1)->Arg(0)->ArgName("tangent");

void BM_SmearedSoftening(benchmark::State& st) {
  const SmearedCrack model({{32000.0, 0.2, Hypothesis::PlaneStress}, 3.0, 8.184, 0.128});
  SmearedCrack::State s;
  for (int i = 0; i < 40; ++i) model.update(s, Voigt(5e-6, -1e-6, 1e-6));
  for (auto _ : st) {
    SmearedCrack::State copy = s;
    benchmark::DoNotOptimize(model.update(copy, kStep));
  }
}
BENCHMARK(BM_SmearedSoftening);

// Material::update over many points, as the Python module's update_many runs it (the same
// update, without the tangent): arg kind 0 intact points (an increment and back, staying
// elastic), 1 cracked points softening further. bench/python_update_bench.py times the same
// from Python.
void BM_MaterialUpdateMany(benchmark::State& st) {
  MaterialParams p{.name = "concrete",
                   .model = ModelKind::Enriched, .elastic = {32000.0, 0.2, Hypothesis::PlaneStress},
                   .tensileStrength = 3.0, .softeningModulus = 8.184, .softeningExponent = 0.128, .bandWidth = 0.05};
  const Material m(p);
  const bool cracked = st.range(0) != 0;
  const auto size = EffectiveSize::fixed(2.5);
  std::vector<MaterialPoint> points(cracked ? 10000 : 100000);
  for (MaterialPoint& q : points)
    for (int i = 0; cracked && i < 40; ++i) m.update(q, Voigt(5e-6, -1e-6, 1e-6), size, SnapBackPolicy::Stop);
  const UpdateOptions options{SnapBackPolicy::Stop, false};
  double sign = 1.0;
  for (auto _ : st) {
    const Voigt d = cracked ? kStep : Voigt(sign * kStep);
    sign = -sign;
    for (MaterialPoint& q : points) {
      const UpdateResult r = m.update(q, d, size, options);
      benchmark::DoNotOptimize(r.stress);
    }
  }
  st.SetItemsProcessed(st.iterations() * static_cast<long>(points.size()));
}
BENCHMARK(BM_MaterialUpdateMany)->Arg(0)->Arg(1)->ArgName("cracked")->Unit(benchmark::kMillisecond);
}  // namespace
