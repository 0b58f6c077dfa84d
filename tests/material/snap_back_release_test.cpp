// The cracked update's predictor/corrector and the snap-back release (TwoPhasePoint::
// releaseSnapBack), against the closed form of the uniaxial point and two states recorded in
// MPM runs where the former single-Newton update stalled or reported a spurious snap-back.
#include <gtest/gtest.h>

#include <cmath>

#include "material/two_phase_point.hpp"
#include "material/uniaxial_closed_form.hpp"
#include "../paper_constants.hpp"

namespace ecm {
namespace {

const DamageLawParams kLaw{test::kE, test::kFt, test::kEp, test::kN};

// Macro strain of the 1D (nu = 0) enriched point on its monotonic branch at integrity x.
double macroStrain(double x, double bigH) {
  return uniaxialMacroStrain(uniaxialBandResponse(kLaw, 0.0, test::kBandWidth, x), test::kE, bigH);
}

// The stable (far) branch root of eps(x) = eps: below the snap-back minimum of eps(x), eps grows
// as x falls (to infinity as x -> 0), so bisection in log x between 1e-14 and that minimum.
double farBranchIntegrity(double eps, double bigH) {
  double xMin = 1.0, eMin = macroStrain(1.0, bigH);
  for (double lx = 0.0; lx > -14.0; lx -= 1e-3) {
    const double e = macroStrain(std::pow(10.0, lx), bigH);
    if (e < eMin) eMin = e, xMin = std::pow(10.0, lx);
  }
  double lo = -14.0, hi = std::log10(xMin);  // eps(lo) > eps > eps(hi)
  for (int it = 0; it < 200; ++it) {
    const double mid = 0.5 * (lo + hi);
    (macroStrain(std::pow(10.0, mid), bigH) > eps ? lo : hi) = mid;
  }
  return std::pow(10.0, 0.5 * (lo + hi));
}

bool stable(const TwoPhasePoint& m, const BandState& b, const Voigt& strain) {
  const BandEquilibrium eq = m.equilibrium(b, strain, b.jump, true);
  return eq.jacobian.determinant() > 0.0 && eq.jacobian.trace() > 0.0;
}

TEST(SnapBackRelease, LandsOnTheClosedFormFarBranchAndKeepsTheFractureEnergy) {
  // H = 1000 mm > h (E + E_p)/E_p = 195.6 mm: under uniaxial strain (nu = 0, so 1D) the first
  // post-peak increment has no stable root. Report returns SnapBack, state untouched; Release
  // lands on the branch where eps(x) = sigma/E + w/H meets the strain again (closed form,
  // material/uniaxial_closed_form.hpp), then loading continues to failure and the dissipation
  // per volume is (h/H) int F dD over the whole path (docs/model.md, identities).
  const double bigH = 1000.0;
  const TwoPhasePoint m(test::paperEnriched(0.0));
  const EffectiveSize size = EffectiveSize::fixed(bigH);
  const double onset = test::kFt / test::kE;
  Voigt strain = Voigt::Zero();
  std::optional<BandState> band;
  const Voigt d(0.01 * onset, 0.0, 0.0);
  for (int i = 0; i < 100 && !band; ++i) ASSERT_TRUE(m.updateIntact(strain, d, size, band, SnapBackPolicy::Stop).converged());
  ASSERT_TRUE(band);
  double dissipation = 0.0;
  BandState reported = *band;
  Voigt reportedStrain = strain;
  const UpdateResult r0 = m.updateCracked(reported, reportedStrain, d, SnapBackPolicy::Stop);
  EXPECT_EQ(r0.status, UpdateStatus::SnapBack);
  EXPECT_EQ(reported.integrity, band->integrity);
  EXPECT_EQ(reportedStrain, strain);

  const UpdateResult r = m.updateCracked(*band, strain, d, SnapBackPolicy::Release);
  ASSERT_TRUE(r.converged());
  EXPECT_TRUE(r.released);
  dissipation += r.dissipation;
  const double x = farBranchIntegrity(strain[0], bigH);
  EXPECT_NEAR(band->integrity, x, 1e-8 * x);
  const double sigma = uniaxialBandResponse(kLaw, 0.0, test::kBandWidth, x).stress;
  EXPECT_NEAR(r.stress[0], sigma, 1e-8 * test::kFt) << "stress drop from f_t' to " << sigma;
  EXPECT_LT(r.stress[0], 0.5 * test::kFt);
  EXPECT_TRUE(stable(m, *band, strain));

  // On to failure: ordinary loading steps, no further release.
  for (int i = 0; i < 400; ++i) {
    const UpdateResult s = m.updateCracked(*band, strain, Voigt(1e-3 * strain[0], 0, 0), SnapBackPolicy::Release);
    ASSERT_TRUE(s.converged());
    EXPECT_FALSE(s.released);
    dissipation += s.dissipation;
  }
  const double expected = test::kBandWidth / bigH * dissipationBetween(kLaw, 1.0, band->integrity);
  EXPECT_NEAR(dissipation, expected, 1e-9 * expected);
  EXPECT_LT(band->integrity, 1e-3);
}

TEST(SnapBackRelease, BelowTheSnapBackSizeNothingIsReleased) {
  // H = 100 mm < 195.6 mm: every increment of a uniaxial strain path has a stable root.
  const TwoPhasePoint m(test::paperEnriched(0.0));
  const EffectiveSize size = EffectiveSize::fixed(100.0);
  Voigt strain = Voigt::Zero();
  std::optional<BandState> band;
  const double step = 0.01 * test::kFt / test::kE;
  for (int i = 0; i < 3000; ++i) {
    const UpdateResult r = band ? m.updateCracked(*band, strain, Voigt(step, 0, 0), SnapBackPolicy::Release)
                                : m.updateIntact(strain, Voigt(step, 0, 0), size, band, SnapBackPolicy::Release);
    ASSERT_TRUE(r.converged()) << i;
    ASSERT_FALSE(r.released) << i;
  }
}

// State of a cracked DEN point (coarse mesh, H = 2.5 mm, f = 0.02) near the right notch tip in
// load path 4b, recorded when the run stopped: mixed-mode band, D = 0.67, the bulk in compression
// along x. The loading K of Eq. (9) has a negative determinant here (the rank-one softening term
// of the non-symmetric band tangent outweighs f/(1-f) a), and no increment of the recorded
// direction has a stable, loading-consistent root: a genuine material snap-back in shear.
struct RecordedState {
  Voigt strain, increment;
  BandState band;
};
RecordedState denNotchTip() {
  RecordedState s;
  s.strain << -0.00010584864836920044, 0.00010266578889842107, 6.851068216746525e-05;
  s.increment << -3.8218005480299262e-07, 5.366139384659339e-07, -1.898950987317096e-07;
  s.band.crackNormal = {0.50795426943120636, 0.86138403756199788};
  s.band.jump = {-1.6385828015663077e-05, 1.4985836341314891e-05};
  s.band.onsetStrain << -4.7703216642277835e-05, 5.5516707333119846e-05, 0.00018663843390615041;
  s.band.integrity = 0.33021893250359619;
  s.band.volumeFraction = 0.02;
  return s;
}

TEST(SnapBackRelease, MixedModeSnapBackOfARecordedDenPointIsReleasedOntoAStableBranch) {
  const TwoPhasePoint m(test::paperEnriched());
  RecordedState s = denNotchTip();
  BandState b = s.band;
  Voigt strain = s.strain;
  // Report: even 4096 sub-steps reach a sub-step with no stable root.
  bool snapped = false;
  for (int i = 0; i < 4096 && !snapped; ++i) {
    const UpdateResult r = m.updateCracked(b, strain, s.increment / 4096, SnapBackPolicy::Stop);
    snapped = r.status == UpdateStatus::SnapBack;
    if (!snapped) {
      ASSERT_TRUE(r.converged());
    }
  }
  ASSERT_TRUE(snapped);
  // There, the loading K of Eq. (9) (on the envelope of the band law) is not positive definite.
  const BandEquilibrium before = m.equilibrium(b, m.bandLaw().envelope(b.integrity), strain, b.jump, true);
  EXPECT_LT(before.jacobian.determinant(), 0.0);
  // Release: the full increment converges, damage grew, continuity holds on a stable branch.
  b = s.band;
  strain = s.strain;
  const UpdateResult r = m.updateCracked(b, strain, s.increment, SnapBackPolicy::Release);
  ASSERT_TRUE(r.converged());
  EXPECT_TRUE(r.released);
  EXPECT_LT(b.integrity, s.band.integrity);
  EXPECT_GT(r.dissipation, 0.0);
  EXPECT_TRUE(stable(m, b, strain));
  EXPECT_LE(m.equilibrium(b, strain, b.jump, false).residual.norm(), 1e-9 * test::kFt);
}

TEST(SnapBackRelease, NewtonStallOnANearlyIntactBandOfTheFineDenIsReleased) {
  // Recorded in the fine DEN 4b run (0.625 mm, CFL 0.6, step 55329, 2026-11-28), where it
  // stopped the run: a band at D = 0.0009, the bulk compressed along x. Newton on the envelope
  // stalls (residual 2e-4 MPa after 60 iterations, 3e-6 with 16 sub-steps) without passing an
  // unstable state, so the update reported NotConverged. The nearest consistent state is a
  // damage jump away (x = 0.884 for a strain increment of 1e-8): Release must find it.
  const TwoPhasePoint m(test::paperEnriched());
  BandState band;
  band.crackNormal = Vec2(0.34804432965025472, 0.93747807686276319);
  band.jump = Vec2(-6.7813686099047065e-06, 1.3839063693808007e-06);
  band.onsetStrain = Voigt(-4.6060899965983799e-05, 8.2739586954506044e-05, 0.00011092476968647125);
  band.integrity = 0.99911569424676394;
  band.volumeFraction = 0.08;
  const Voigt strain0(-0.00012074431839015152, 0.00011036042654953005, 1.8663507050920813e-05);
  const Voigt increment(6.6041332149405546e-09, 9.5372468018902191e-09, -5.7981418758228075e-09);
  BandState b = band;
  Voigt strain = strain0;
  const UpdateResult reported = m.updateCracked(b, strain, increment, SnapBackPolicy::Stop);
  EXPECT_EQ(reported.status, UpdateStatus::NotConverged) << "the stall this test was written for is gone";
  const UpdateResult r = m.updateCracked(b, strain, increment, SnapBackPolicy::Release);
  ASSERT_TRUE(r.converged()) << toString(r.status) << ", residual " << r.residual;
  EXPECT_TRUE(r.released);
  EXPECT_LT(b.integrity, 0.95);  // a damage jump, not a round-off step
  EXPECT_GT(r.dissipation, 0.0);
  EXPECT_TRUE(stable(m, b, strain));
  EXPECT_LE(m.equilibrium(b, strain, b.jump, false).residual.norm(), 1e-9 * test::kFt);  // Eq. (6)
  // Consistency: the driving force sits on the loading surface of the new damage, Y = F(x).
  const BandEquilibrium eq = m.equilibrium(b, strain, b.jump, false);
  EXPECT_NEAR(eq.band.drivingForce / damageFunction(m.bandLaw().law(), b.integrity), 1.0, 1e-9);
}

TEST(CrackedUpdate, NearlyFailedBandUnloadingInShearConvergesElastically) {
  // Recorded in the notched tension block of tests/mpm/threads_test.cpp (H = 5 mm, D = 0.987):
  // a band exactly on its loading surface, an increment that unloads it. The former update
  // (Newton from the loading tangent, switching branches inside the iteration) cycled between
  // loading and unloading; the elastic predictor (Eq. (9) with a_L = x a) solves it in one step.
  const TwoPhasePoint m(test::paperEnriched());
  BandState b;
  b.crackNormal = {0.083717712088610105, -0.99648951057331692};
  b.jump = {1.7362350308547104e-05, -0.00033579279775775418};
  b.onsetStrain << -5.3349371853134725e-06, 9.2178247818208497e-05, -1.6501146867616467e-05;
  b.integrity = 0.013334503739067066;
  b.volumeFraction = 0.01;
  Voigt strain(-7.3660606250015885e-06, 0.0001589369263255925, -2.3054140240754505e-05);
  const Voigt d(-2.4834870819812561e-07, -3.4598335287910377e-08, -1.1732933864320074e-07);
  const double x0 = b.integrity;
  const UpdateResult r = m.updateCracked(b, strain, d, SnapBackPolicy::Stop);
  ASSERT_TRUE(r.converged()) << toString(r.status);
  EXPECT_FALSE(r.released);
  EXPECT_EQ(b.integrity, x0);
  EXPECT_EQ(r.dissipation, 0.0);
  EXPECT_LE(r.iterations, 2);
}

}  // namespace
}  // namespace ecm
