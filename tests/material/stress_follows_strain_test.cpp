// Material::stressFollowsStrain: an elastic point's and an intact enriched point's stress is
// a : strain (Eq. (4) with no band), and every update of such a point ends with exactly that
// product, bit for bit, whichever path it takes (the closed form, the cheap bound of
// TwoPhasePoint::updateIntact, the onset test of updateIntactSlow, sub-stepping). The explicit
// MPM stores such stresses only when they are read (docs/performance.md), which is right only
// if recomputing them from the strain gives the same bits.
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <random>

#include "material/material.hpp"
#include "../paper_constants.hpp"

namespace ecm {
namespace {

bool sameBits(const Voigt& a, const Voigt& b) {
  for (int c = 0; c < 3; ++c)
    if (std::bit_cast<std::uint64_t>(a[c]) != std::bit_cast<std::uint64_t>(b[c])) return false;
  return true;
}

// Random strains up to 1.2 x the uniaxial onset strain in every direction, random increments
// up to a quarter of it: some stay far from onset, some end between the cheap bound and onset,
// some open a band.
void expectUpdatesEndWithTheClosedForm(const MaterialParams& params, long& nearOnset, long& opened) {
  const Material m(params);
  std::mt19937_64 rng(20261204);
  const double onset = test::kFt / test::kE;
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const EffectiveSize size = EffectiveSize::fixed(0.625);
  for (int k = 0; k < 20000; ++k) {
    MaterialPoint p;
    p.strain = 1.2 * onset * Voigt(u(rng), u(rng), u(rng));
    const Voigt d = 0.25 * onset * Voigt(u(rng), u(rng), u(rng));
    const Voigt start = m.intactStress(p.strain);
    if (params.model == ModelKind::Enriched && !m.enriched()->staysIntact(start)) continue;  // cracked already
    const UpdateResult r = m.update(p, d, size, SnapBackPolicy::Stop);
    ASSERT_TRUE(r.converged());
    if (p.band) {
      ++opened;
      continue;
    }
    ASSERT_TRUE(m.stressFollowsStrain(false));
    ASSERT_TRUE(sameBits(r.stress, m.intactStress(p.strain))) << "sample " << k;
    if (params.model == ModelKind::Enriched && !m.enriched()->surelyIntact(r.stress)) ++nearOnset;
  }
}

TEST(StressFollowsStrain, AnIntactEnrichedPointsUpdateEndsWithItsClosedForm) {
  long nearOnset = 0, opened = 0;
  expectUpdatesEndWithTheClosedForm(test::paperConcreteMaterial(), nearOnset, opened);
  EXPECT_GT(nearOnset, 500) << "updates past the cheap bound that stay intact (updateIntactSlow's path)";
  EXPECT_GT(opened, 500);
}

TEST(StressFollowsStrain, WithTheSecondBandOptionToo) {
  MaterialParams params = test::paperConcreteMaterial();
  params.secondBand = SecondBandOption::Orthogonal;
  long nearOnset = 0, opened = 0;
  expectUpdatesEndWithTheClosedForm(params, nearOnset, opened);
  EXPECT_GT(nearOnset, 500);
}

TEST(StressFollowsStrain, AnElasticPointsUpdateEndsWithItsClosedForm) {
  MaterialParams params;
  params.model = ModelKind::LinearElastic;
  params.elastic = {test::kE, test::kNu, Hypothesis::PlaneStrain};
  long nearOnset = 0, opened = 0;
  expectUpdatesEndWithTheClosedForm(params, nearOnset, opened);
  EXPECT_EQ(opened, 0);
}

TEST(StressFollowsStrain, NotACrackedOrSmearedPoint) {
  const Material enriched(test::paperConcreteMaterial());
  EXPECT_TRUE(enriched.stressFollowsStrain(false));
  EXPECT_FALSE(enriched.stressFollowsStrain(true));
  MaterialParams smeared = test::paperConcreteMaterial();
  smeared.model = ModelKind::SmearedCrack;
  EXPECT_FALSE(Material(smeared).stressFollowsStrain(false));
}

}  // namespace
}  // namespace ecm
