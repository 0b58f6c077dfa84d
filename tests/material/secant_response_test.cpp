// The secant response of an unloading band (material/secant_response.hpp, docs/model.md "The
// secant response of an unloading band"): affine maps of the strain that replace the elastic
// predictor's solve while the band's damage is frozen. Expected values come from the model itself:
// - the maps solve traction continuity, Eq. (6), with a_L = x0 a, for any strain (residual at
//   round-off, 1e-9 f_t');
// - along random strain paths, an update that takes the maps gives the predictor's state to
//   round-off (the predictor's own tolerance is 1e-10 f_t'), and a loading update is the full
//   update bit for bit;
// - maps built for another band are never used.
#include <gtest/gtest.h>

#include <random>

#include "material/material.hpp"
#include "../paper_constants.hpp"

namespace ecm {
namespace {

std::mt19937_64& rng() {
  static std::mt19937_64 r(20261203);
  return r;
}
double uniform(double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng()); }

// A cracked point of the paper's concrete: tension at angle `angle` to onset and `beyond` past it.
MaterialPoint crackedPoint(const Material& m, double angle, double beyond) {
  MaterialPoint p;
  const Voigt direction = rotateStrain(Voigt(1.0, -0.2, 0.0), angle);
  const EffectiveSize size = EffectiveSize::fixed(0.625);
  for (int i = 0; i < 400 && !p.band; ++i) m.update(p, 2e-6 * direction, size, UpdateOptions(SnapBackPolicy::Release, false));
  for (int i = 0; i < 20; ++i) m.update(p, beyond / 20 * direction, size, UpdateOptions(SnapBackPolicy::Release, false));
  return p;
}

TEST(SecantResponse, TheMapsSolveTractionContinuityWithTheDamageFrozen) {
  const Material m(test::paperConcreteMaterial());
  const TwoPhasePoint& e = *m.enriched();
  int checked = 0;
  for (int k = 0; k < 50; ++k) {
    const MaterialPoint p = crackedPoint(m, uniform(-1.5, 1.5), uniform(1e-6, 2e-4));
    ASSERT_TRUE(p.band);
    const SecantResponse s = e.secantResponse(*p.band);
    EXPECT_TRUE(s.builtFor(*p.band));
    const BandDamageLaw::LoadingSurface frozen{p.band->integrity, std::numeric_limits<double>::infinity()};
    for (int j = 0; j < 20; ++j) {
      const Voigt eps = p.strain + Voigt(uniform(-1e-4, 1e-4), uniform(-1e-4, 1e-4), uniform(-1e-4, 1e-4));
      const Vec2 jump = s.jumpOfStrain * eps + s.jumpAtZeroStrain;
      const BandEquilibrium eq = e.equilibrium(*p.band, frozen, eps, jump, false);
      EXPECT_LT(eq.residual.norm(), 1e-9 * test::kFt) << "band " << k;                 // Eq. (6)
      const Voigt aBand = s.bandStressOfStrain * eps + s.bandStressAtZeroStrain;
      EXPECT_LT((aBand - e.stiffness() * eq.bandStrain).norm(), 1e-9 * test::kFt);     // a eps_L, Eq. (3)
      ++checked;
    }
  }
  EXPECT_EQ(checked, 1000);
}

// One random path, run twice from the same state before every increment: with the secant
// response kept (as the MPM keeps it) and without (the predictor's solve).
struct PathCounts {
  int unloadingByMaps = 0, loading = 0;
};

void comparePaths(const Material& m, std::uint64_t seed, PathCounts& counts) {
  rng().seed(seed);
  MaterialPoint reference = crackedPoint(m, uniform(-1.5, 1.5), uniform(1e-6, 1e-4));
  ASSERT_TRUE(reference.band);
  SecantResponse secant;
  const EffectiveSize size = EffectiveSize::fixed(0.625);
  const UpdateOptions options(SnapBackPolicy::Release, false);
  Voigt direction = -Voigt(1.0, 0.0, 0.0);
  for (int i = 0; i < 300; ++i) {
    if (i % 10 == 0) direction = Voigt(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)).normalized();
    const Voigt d = std::pow(10.0, uniform(-7.0, -4.5)) * direction;
    MaterialPoint cached = reference;
    OpenedBands none, none2;
    const UpdateResult r = m.update({reference.strain, nullptr, &*reference.band}, d, size, none, options);
    const UpdateResult c = m.update({cached.strain, nullptr, &*cached.band, nullptr, &secant}, d, size, none2, options);
    ASSERT_EQ(r.status, c.status) << "increment " << i;
    if (!r.converged()) continue;
    EXPECT_TRUE(secant.builtFor(*cached.band) || cached.band->integrity != secant.integrity);
    if (cached.band->integrity != secant.integrity) {
      // The band loaded: the full update, bit for bit.
      ++counts.loading;
      EXPECT_EQ(c.stress, r.stress) << "increment " << i;
      EXPECT_EQ(cached.band->jump, reference.band->jump);
      EXPECT_EQ(cached.band->integrity, reference.band->integrity);
      continue;
    }
    EXPECT_EQ(cached.band->integrity, reference.band->integrity) << "increment " << i;
    EXPECT_LT((c.stress - r.stress).norm(), 1e-9 * test::kFt) << "increment " << i;
    EXPECT_LE((cached.band->jump - reference.band->jump).norm(), 1e-9 * reference.band->jump.norm() + 1e-15);
    EXPECT_EQ(cached.strain, reference.strain);
    if (c.iterations == 0 && r.iterations > 0) ++counts.unloadingByMaps;
  }
}

TEST(SecantResponse, AlongRandomPathsItGivesThePredictorsStateAndLoadsBitForBit) {
  PathCounts counts;
  for (const Hypothesis hyp : {Hypothesis::PlaneStress, Hypothesis::PlaneStrain}) {
    MaterialParams params = test::paperConcreteMaterial();
    params.elastic.hypothesis = hyp;
    const Material m(params);
    for (std::uint64_t seed = 1; seed <= 20; ++seed) comparePaths(m, seed, counts);
  }
  // Both paths were taken many times (otherwise the comparison above proves nothing).
  EXPECT_GT(counts.unloadingByMaps, 2000);
  EXPECT_GT(counts.loading, 100);
}

TEST(SecantResponse, MapsBuiltForAnotherBandAreRebuiltNotUsed) {
  const Material m(test::paperConcreteMaterial());
  const TwoPhasePoint& e = *m.enriched();
  rng().seed(7);
  const MaterialPoint a = crackedPoint(m, 0.3, 5e-5), b = crackedPoint(m, -0.9, 2e-5);
  ASSERT_TRUE(a.band && b.band);
  SecantResponse stale = e.secantResponse(*a.band);
  ASSERT_FALSE(stale.builtFor(*b.band));
  const Voigt unload = -1e-5 * (b.strain / b.strain.norm());
  MaterialPoint withStale = b, reference = b;
  const UpdateOptions options(SnapBackPolicy::Release, false);
  const UpdateResult r = e.updateCracked(*reference.band, reference.strain, unload, options);
  const UpdateResult c = e.updateCracked(*withStale.band, stale, withStale.strain, unload, options);
  ASSERT_TRUE(r.converged() && c.converged());
  EXPECT_EQ(withStale.band->integrity, reference.band->integrity);  // it unloaded
  EXPECT_TRUE(stale.builtFor(*withStale.band));
  EXPECT_EQ(c.iterations, 0);  // by the (rebuilt) maps
  EXPECT_LT((c.stress - r.stress).norm(), 1e-9 * test::kFt);
  // A band state that differs from the maps' key in one field only is not theirs either.
  BandState moved = *b.band;
  moved.onsetStrain[2] = std::nextafter(moved.onsetStrain[2], 1.0);
  EXPECT_FALSE(e.secantResponse(*b.band).builtFor(moved));
}

TEST(SecantResponse, WithTheTangentTheUpdateIsThePredictorsBitForBit) {
  const Material m(test::paperConcreteMaterial());
  const TwoPhasePoint& e = *m.enriched();
  rng().seed(11);
  MaterialPoint p = crackedPoint(m, 0.2, 3e-5), q = p;
  SecantResponse secant;
  const Voigt unload = -2e-5 * (p.strain / p.strain.norm());
  const UpdateResult r = e.updateCracked(*p.band, p.strain, unload, UpdateOptions(SnapBackPolicy::Release, true));
  const UpdateResult c = e.updateCracked(*q.band, secant, q.strain, unload, UpdateOptions(SnapBackPolicy::Release, true));
  EXPECT_EQ(r.stress, c.stress);
  EXPECT_EQ(r.tangent, c.tangent);
  EXPECT_EQ(p.band->jump, q.band->jump);
  EXPECT_LT(secant.integrity, 0.0);  // not built: the implicit solver needs the tangent anyway
}

}  // namespace
}  // namespace ecm
