// Numerical stability at the extremes: huge increments, D -> 1, compression, rotating principal
// axes, f near 1 and f near 0 (far past the snap-back size).
#include <gtest/gtest.h>

#include <cmath>

#include "enriched_uniaxial.hpp"
#include "material/material.hpp"
#include "material/smeared_crack.hpp"

namespace ecm {
namespace {

bool finite(const UpdateResult& r) { return r.stress.allFinite() && r.tangent.allFinite() && std::isfinite(r.dissipation); }

TEST(Extremes, OneHugeIncrementEqualsManySmallOnes) {
  // Monotonic proportional loading: the converged state depends only on the final strain, so
  // 1e-2 strain in one step must give the state of 1000 steps (and the same dissipation, which
  // is int F dD between the same integrities).
  TwoPhasePoint model(test::paperEnriched());
  const auto size = EffectiveSize::fixed(2.5);
  const Voigt total(1e-2, -2e-3, 0.0);
  EnrichedState one, many;
  const UpdateResult big = model.update(one, total, size);
  ASSERT_TRUE(big.converged()) << toString(big.status) << " residual " << big.residual;
  double dissipated = 0.0;
  UpdateResult small;
  for (int i = 0; i < 1000; ++i) {
    small = model.update(many, total / 1000, size);
    ASSERT_TRUE(small.converged());
    dissipated += small.dissipation;
  }
  EXPECT_TRUE(finite(big));
  EXPECT_LE((big.stress - small.stress).norm(), 1e-9 * test::kFt);
  EXPECT_NEAR(one.band->integrity, many.band->integrity, 1e-9 * many.band->integrity);
  EXPECT_NEAR(big.dissipation, dissipated, 1e-6 * dissipated);
}

TEST(Extremes, DamageApproachingOneLeavesNoNaN) {
  // Strains far beyond failure: stress -> 0, integrity stays positive, nothing is NaN.
  TwoPhasePoint model(test::paperEnriched());
  EnrichedState s;
  const auto size = EffectiveSize::fixed(1.0);
  UpdateResult r;
  for (double d : {1e-4, 1e-2, 1.0, 10.0}) {
    r = model.update(s, Voigt(d, 0.0, 0.0), size);
    ASSERT_TRUE(r.converged()) << toString(r.status);
    ASSERT_TRUE(finite(r));
    EXPECT_GE(r.dissipation, 0.0);
  }
  EXPECT_GT(s.band->integrity, 0.0);
  EXPECT_LT(s.band->integrity, 1e-12);
  EXPECT_LT(std::abs(s.band->crackNormal.dot(r.stress.head<2>().cwiseProduct(s.band->crackNormal))), 1e-6 * test::kFt);
  SmearedCrack smeared(test::paperBand());
  SmearedCrack::State ss;
  const UpdateResult rs = smeared.update(ss, Voigt(10.0, 0.0, 0.0));
  EXPECT_TRUE(finite(rs));
  EXPECT_GT(ss.integrity, 0.0);
}

TEST(Extremes, CompressionAloneNeverCracks) {
  // Eq. (12): no positive principal stress, no driving force, no band, no dissipation.
  TwoPhasePoint model(test::paperEnriched());
  EnrichedState s;
  for (int i = 0; i < 100; ++i) {
    const UpdateResult r = model.update(s, Voigt(-1e-4, -3e-5, 2e-5), EffectiveSize::fixed(2.5));
    ASSERT_TRUE(r.converged());
    EXPECT_EQ(r.dissipation, 0.0);
    EXPECT_TRUE(r.stress.isApprox(model.stiffness() * s.strain));
  }
  EXPECT_FALSE(s.band);
}

TEST(Extremes, CrackNormalStaysFixedWhenPrincipalAxesRotateByNinetyDegrees) {
  // After cracking in x, tension along y: n stays (1, 0), traction continuity (6) still holds
  // and damage never decreases; the y stress is carried by the bulk and the frozen band.
  TwoPhasePoint model(test::paperEnriched());
  EnrichedState s;
  const auto size = EffectiveSize::fixed(2.5);
  for (int i = 0; i < 20; ++i) ASSERT_TRUE(model.update(s, Voigt(1e-5, 0.0, 0.0), size).converged());
  ASSERT_TRUE(s.band);
  const Vec2 normal = s.band->crackNormal;
  EXPECT_NEAR(normal[0], 1.0, 1e-12);
  double damage = s.band->damage();
  for (int i = 0; i < 40; ++i) {
    const UpdateResult r = model.update(s, Voigt(-2e-6, 2e-5, 0.0), size);
    ASSERT_TRUE(r.converged());
    EXPECT_EQ(s.band->crackNormal, normal);
    EXPECT_GE(s.band->damage(), damage);
    damage = s.band->damage();
    EXPECT_LE(model.equilibrium(*s.band, s.strain, s.band->jump, false).residual.norm(), 1e-9 * test::kFt);
  }
}

TEST(Extremes, VolumeFractionNearOne) {
  // f = 0.99: the point is almost all band; it must still converge through complete failure
  // and dissipate G_F per H (docs/model.md, identities).
  const double bigH = test::kBandWidth / 0.99;
  test::EnrichedRun run(test::paperEnriched(0.0), bigH);
  ASSERT_TRUE(run.step(test::kFt / test::kE));
  double d = 1e-7;
  while (run.state.strain[0] < 5.0) {
    ASSERT_TRUE(run.step(d));
    d *= 1.02;
  }
  const double gf = test::kBandWidth * dissipationToFailure({test::kE, test::kFt, test::kEp, test::kN});
  EXPECT_NEAR(bigH * run.dissipated, gf, 0.01 * gf);
}

TEST(Extremes, VolumeFractionNearZeroReportsTheSnapBackCleanly) {
  // f = 1e-6 (H = 50 m, far past the snap-back size h (E + E_p)/E_p = 195.6 mm): under strain
  // control the first softening increment has no equilibrium branch. It must come back as a
  // flagged update with the state unchanged, never as NaN or negative dissipation.
  TwoPhasePoint model(test::paperEnriched(0.0));
  EnrichedState s;
  const auto size = EffectiveSize::fixed(test::kBandWidth / 1e-6);
  ASSERT_TRUE(model.update(s, Voigt(test::kFt / test::kE, 0.0, 0.0), size, SnapBackPolicy::Stop).converged());
  ASSERT_TRUE(s.band);
  const EnrichedState before = s;
  const UpdateResult r = model.update(s, Voigt(1e-7, 0.0, 0.0), size, SnapBackPolicy::Stop);
  EXPECT_EQ(r.status, UpdateStatus::SnapBack);
  EXPECT_TRUE(r.stress.allFinite());
  EXPECT_GE(r.dissipation, 0.0);
  EXPECT_EQ(s.strain, before.strain);
  EXPECT_EQ(s.band->jump, before.band->jump);
  EXPECT_EQ(s.band->integrity, before.band->integrity);
  // Unloading from the same state is fine: the secant branch is stable.
  EXPECT_TRUE(model.update(s, Voigt(-1e-6, 0.0, 0.0), size, SnapBackPolicy::Stop).converged());
}

TEST(Extremes, SnapBackSetsInJustAboveTheOneDimensionalSize) {
  // docs/model.md, identities: C of Eq. (9) vanishes at H = h (E + E_p) / E_p (1D, nu = 0): just below it the
  // first softening increment converges, just above it is reported as a snap-back.
  for (const auto& [ratio, expected] : {std::pair{0.999, UpdateStatus::Converged}, std::pair{1.001, UpdateStatus::SnapBack}}) {
    TwoPhasePoint model(test::paperEnriched(0.0));
    EnrichedState s;
    const auto size = EffectiveSize::fixed(ratio * test::kSnapBackSize);
    ASSERT_TRUE(model.update(s, Voigt(test::kFt / test::kE, 0.0, 0.0), size, SnapBackPolicy::Stop).converged());
    EXPECT_EQ(model.update(s, Voigt(1e-9, 0.0, 0.0), size, SnapBackPolicy::Stop).status, expected) << "H / H_snap = " << ratio;
  }
}

}  // namespace
}  // namespace ecm

namespace ecm {
namespace {

TEST(Extremes, IntegrityAtTheUnderflowLimitKeepsTheTangentFinite) {
  // Fuzzer finding (fuzz/corpus/material_update/material_update-crash-4487...): with n = 0.001
  // a huge strain drives x = 1 - D to ~1e-315, where dF/dx overflows; the tangent was NaN.
  SmearedCrack model({{31.6244, -0.989639, Hypothesis::PlaneStress}, 0.0316244, 0.00100507, 0.001});
  SmearedCrack::State s;
  const UpdateResult r = model.update(s, Voigt(9.9276723756738416, 9.9222106138812531, 1.2502032895507427));
  ASSERT_TRUE(r.converged());
  EXPECT_LT(s.integrity, 1e-300);
  EXPECT_TRUE(r.stress.allFinite());
  EXPECT_TRUE(r.tangent.allFinite());
  EXPECT_GE(r.dissipation, 0.0);
}

TEST(Extremes, HugeJumpIncrementSamplesItsPathWithoutOverflow) {
  // Fuzzer finding (fuzz/corpus/material_update/int-cast-path-samples): a jump increment of some
  // 6e9 kJumpCheck h made the path's sample count overflow an int before it was clamped
  // (undefined behaviour, reported by UBSan under scripts/sanitize.sh). The harness's input
  // decoded: f = h/H = 1 - 1e-6, E 1 MPa with f_t' 1000 MPa, strain increments of 1e7.
  MaterialParams p{.name = "huge-jump",
                   .model = ModelKind::Enriched, .elastic = {1.0, 0.3100784313725491, Hypothesis::PlaneStrain},
                   .tensileStrength = 1000.0, .softeningModulus = 1e6, .softeningExponent = 0.499,
                   .bandWidth = 9.585458220833413};
  const Material m(p);
  const auto size = EffectiveSize::fixed(9.585468202229087);
  MaterialPoint point;
  for (const Voigt& d : {Voigt(-0.10207124692610127, 0.00020131780220880693, 5.149990289062503e-05),
                         Voigt(-8605712.160094863, 5209252.544834244, 8659624.217479952),
                         Voigt(33839.299224698545, 254815.40557171317, 254815.40557171317),
                         Voigt(10000000.0, -9995117.112993058, -9960936.903944457)}) {
    const MaterialPoint before = point;
    const UpdateResult r = m.update(point, d, size, SnapBackPolicy::Stop);
    if (!r.converged()) {  // a refused increment leaves the state as it was
      EXPECT_EQ(point.strain, before.strain);
      continue;
    }
    EXPECT_TRUE(finite(r));
    EXPECT_GE(r.dissipation, 0.0);
  }
}

}  // namespace
}  // namespace ecm
