// The enriched two-phase point, Eqs. (1)-(10), against closed forms and the energy identity.
#include "material/two_phase_point.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "enriched_uniaxial.hpp"
#include "material/material.hpp"
#include "material/uniaxial_closed_form.hpp"

namespace ecm {
namespace {

using test::EnrichedRun;
const DamageLawParams kLaw{test::kE, test::kFt, test::kEp, test::kN};

// Drive to complete failure with increments growing geometrically after onset.
void driveToFailure(EnrichedRun& run, double firstIncrement, double growth, double maxStrain) {
  const double onset = test::kFt / test::kE;
  ASSERT_TRUE(run.step(onset));
  double d = firstIncrement;
  while (run.state.strain[0] < maxStrain) {
    ASSERT_TRUE(run.step(d)) << "failed at strain " << run.state.strain[0];
    d *= growth;
  }
}

class EnrichedEnergy : public ::testing::TestWithParam<std::tuple<double, double>> {};

// Peak of the closed form (material/uniaxial_closed_form.hpp): f_t' for nu = 0, 3.057 MPa for 0.2.
double closedFormPeak(double nu) {
  double peak = 0.0;
  for (double lx = 0.0; lx > -12.0; lx -= 1e-4)
    peak = std::max(peak, uniaxialBandResponse(kLaw, nu, test::kBandWidth, std::pow(10.0, lx)).stress);
  return peak;
}

TEST_P(EnrichedEnergy, DissipatesFractureEnergyForAnyEffectiveSize) {
  // Identity (docs/model.md): H x (dissipation per unit volume) = h int_0^1 F dD = G_F, whatever H
  // and whatever nu (the split removes nothing in uniaxial tension).
  const auto [ratio, nu] = GetParam();
  const double bigH = ratio * test::kBandWidth;
  EnrichedRun run(test::paperEnriched(nu), bigH);
  driveToFailure(run, 1e-8 * (1.0 + test::kBandWidth / bigH * 1e3), 1.01, 10.0 * test::kBandWidth / bigH + 1e-2);
  const double gf = test::kBandWidth * dissipationToFailure(kLaw);
  EXPECT_NEAR(bigH * run.dissipated, gf, 0.01 * gf);
  // ... and the work-based figure agrees in monotonic tension (trapezoid rule: 1%).
  const double stored = 0.5 * run.stress[0] * run.state.strain[0];
  EXPECT_NEAR(bigH * (run.work - stored), gf, 0.01 * gf);
  // Peak: f_t' exactly at onset for nu = 0; for nu = 0.2 that of the closed form (sampled).
  if (nu == 0.0) {
    EXPECT_NEAR(run.peak, test::kFt, 1e-8 * test::kFt);
  } else {
    const double exact = closedFormPeak(nu);
    EXPECT_LE(run.peak, exact * (1.0 + 1e-9));
    EXPECT_GE(run.peak, exact - 1e-4 * test::kFt);
  }
}

// H/h from 1.01 to just below the snap-back size h (E + E_p)/E_p, i.e. H/h < 3911 (nu = 0;
// with nu = 0.2 the band's curve snaps back only beyond H = 323.7 mm).
INSTANTIATE_TEST_SUITE_P(RatiosHOverh, EnrichedEnergy,
                         ::testing::Combine(::testing::Values(1.01, 10.0, 100.0, 1000.0, 3900.0),
                                            ::testing::Values(0.0, test::kNu)));

TEST(TwoPhasePoint, UniaxialStressWithPoissonFollowsTheFrozenLateralBandClosedForm) {
  // With nu = 0.2 the band's lateral strain stays at its onset value -nu f_t'/E, so the band is
  // laterally constrained: its traction follows uniaxialBandResponse(x) (derived from Eqs. (11)-(12)),
  // the macro strain is eps = sigma/E + w/H with w = h (eps_L - sigma/E) (docs/model.md pitfall 4),
  // and the peak exceeds f_t' by up to 1/sqrt(1 - nu^2) (3.062 MPa).
  const double bigH = 10.0;
  EnrichedRun run(test::paperEnriched(), bigH);
  ASSERT_TRUE(run.step(test::kFt / test::kE));
  double worst = 0.0, d = 1e-7;
  for (int i = 0; i < 600; ++i, d *= 1.01) {
    ASSERT_TRUE(run.step(d));
    const BandState& b = *run.state.band;
    const auto exact = uniaxialBandResponse(kLaw, test::kNu, test::kBandWidth, b.integrity);
    const double strain = uniaxialMacroStrain(exact, test::kE, bigH);
    worst = std::max({worst, std::abs(run.stress[0] - exact.stress) / test::kFt,
                      std::abs(run.state.strain[0] - strain) / strain});
  }
  EXPECT_LT(worst, 1e-8);
  EXPECT_GT(run.peak, test::kFt * 1.015);
  EXPECT_LT(run.peak, test::kFt / std::sqrt(1.0 - test::kNu * test::kNu));
  // Energy identity still holds (docs/model.md, identities): nothing is removed by the split.
  double d2 = d;
  while (run.state.strain[0] < 0.2) {
    ASSERT_TRUE(run.step(d2));
    d2 *= 1.02;
  }
  const double gf = test::kBandWidth * dissipationToFailure(kLaw);
  EXPECT_NEAR(bigH * run.dissipated, gf, 0.01 * gf);
}

TEST(TwoPhasePoint, UniaxialResponseMatchesTheOneDimensionalClosedForm) {
  // nu = 0: eps = sigma/E + w(sigma)/H with sigma(x) = uniaxialStress(x), eps_L = sigma/(x E).
  const double bigH = 50.0;
  EnrichedRun run(test::paperEnriched(0.0), bigH);
  ASSERT_TRUE(run.step(test::kFt / test::kE));
  double d = 1e-8;
  for (int i = 0; i < 800; ++i, d *= 1.01) {
    ASSERT_TRUE(run.step(d));
    const double x = run.state.band->integrity;
    const double sigma = uniaxialStress(kLaw, x);
    const double w = test::kBandWidth * (sigma / (x * test::kE) - sigma / test::kE);
    EXPECT_NEAR(run.stress[0], sigma, 1e-9 * test::kFt);
    EXPECT_NEAR(run.state.strain[0], sigma / test::kE + w / bigH, 1e-9 * run.state.strain[0]);
  }
}

TEST(TwoPhasePoint, TractionIsContinuousAcrossTheBandAtConvergence) {
  // Eq. (6): |(sigma - sigma_L) n| <= 1e-9 f_t' after every converged increment, on a path
  // of tension, then shear, then partial unloading.
  TwoPhasePoint model(test::paperEnriched());
  EnrichedState s;
  const auto size = EffectiveSize::fixed(2.5);
  std::vector<Voigt> path;
  for (int i = 0; i < 30; ++i) path.emplace_back(1e-5, 0.0, 0.0);
  for (int i = 0; i < 30; ++i) path.emplace_back(0.0, 0.0, 2e-5);
  for (int i = 0; i < 10; ++i) path.emplace_back(-1e-5, 0.0, -1e-5);
  for (const Voigt& d : path) {
    const UpdateResult r = model.update(s, d, size);
    ASSERT_TRUE(r.converged()) << toString(r.status);
    if (!s.band) continue;
    const BandEquilibrium eq = model.equilibrium(*s.band, s.strain, s.band->jump, false);
    EXPECT_LE(eq.residual.norm(), 1e-9 * test::kFt);
    EXPECT_TRUE(eq.stress.isApprox(r.stress, 1e-12));
  }
  ASSERT_TRUE(s.band);
  EXPECT_GT(s.band->damage(), 0.5);
}

TEST(TwoPhasePoint, RotatedPathGivesRotatedStressAndCrackNormal) {
  // Objectivity: the model is isotropic until onset and the crack normal is a principal
  // direction, so rotating the strain path by theta rotates stress and normal by theta.
  TwoPhasePoint model(test::paperEnriched());
  const auto size = EffectiveSize::fixed(5.0);
  for (double theta : {0.3, 1.0, std::numbers::pi / 2, 2.5}) {
    EnrichedState a, b;
    for (int i = 0; i < 60; ++i) {
      const Voigt d = i < 40 ? Voigt(4e-6, -1e-6, 1e-6) : Voigt(1e-6, 2e-6, 6e-6);
      const UpdateResult ra = model.update(a, d, size);
      const UpdateResult rb = model.update(b, rotateStrain(d, theta), size);
      ASSERT_TRUE(ra.converged() && rb.converged());
      EXPECT_LE((rotateStress(ra.stress, theta) - rb.stress).norm(), 1e-9 * test::kFt) << "theta " << theta;
    }
    ASSERT_TRUE(a.band && b.band);
    const Vec2 rotated = Eigen::Rotation2Dd(theta) * a.band->crackNormal;
    EXPECT_NEAR(std::abs(rotated.dot(b.band->crackNormal)), 1.0, 1e-12);
    EXPECT_NEAR(a.band->damage(), b.band->damage(), 1e-12);
  }
}

TEST(TwoPhasePoint, OnsetIsSplitAtTheExactPoint) {
  // docs/model.md pitfall 1: one big increment through onset gives the same state as stopping
  // exactly at onset and continuing (the onset strain is the root of Eq. (12) with D = 0).
  TwoPhasePoint model(test::paperEnriched(0.0));
  const auto size = EffectiveSize::fixed(10.0);
  const Voigt direction(1.0, 0.0, 0.3);
  EnrichedState once, twice;
  ASSERT_TRUE(model.update(once, 3e-4 * direction, size).converged());
  // Uniaxial-strain-with-shear onset: solve Y(alpha) = F(0) in closed form via bisection here.
  double lo = 0.0, hi = 3e-4;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (model.intactDrivingForce(mid * direction) < model.bandLaw().onsetDrivingForce() ? lo : hi) = mid;
  }
  ASSERT_TRUE(model.update(twice, hi * direction, size).converged());
  ASSERT_TRUE(model.update(twice, (3e-4 - hi) * direction, size).converged());
  ASSERT_TRUE(once.band && twice.band);
  EXPECT_LE((once.band->onsetStrain - twice.band->onsetStrain).norm(), 1e-15);
  EXPECT_NEAR(once.band->integrity, twice.band->integrity, 1e-9);
  EXPECT_LE((once.band->crackNormal - twice.band->crackNormal).norm(), 1e-9);
}

TEST(TwoPhasePoint, TheClosedFormStressIsTakenExactlyWhereTheUpdateOpensNoBand) {
  // Material::closedFormStress (the explicit MPM's fast path) must take every intact point that
  // Material::update would leave intact, with the same strain and stress, and no other: the
  // exact onset test of Eq. (12), not only its cheap bound (which refuses, for one, every point
  // under compression, where Y = 0). Random strains from 0.1 to 10 times the onset strain in
  // every direction and sign, from a prestrained state.
  const Material m(test::paperConcreteMaterial());
  const auto size = EffectiveSize::fixed(10.0);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), decade(-1.0, 1.0);
  const double onset = test::kFt / test::kE;
  int closedForm = 0, boundRefused = 0;
  for (int i = 0; i < 20000; ++i) {
    const Voigt start = onset * std::pow(10.0, decade(rng)) * Voigt(unit(rng), unit(rng), unit(rng)).normalized();
    const Voigt increment = 0.1 * onset * Voigt(unit(rng), unit(rng), unit(rng));
    if (!(m.enriched()->intactDrivingForce(start) < m.enriched()->bandLaw().onsetDrivingForce())) continue;  // intact start
    Voigt strain = start, stress;
    const bool closed = m.closedFormStress(increment, false, strain, stress);
    MaterialPoint point;
    point.strain = start;
    const UpdateResult r = m.update(point, increment, size, SnapBackPolicy::Stop);
    ASSERT_TRUE(r.converged());
    EXPECT_EQ(closed, !point.band) << start.transpose() << " + " << increment.transpose();
    if (!closed) continue;
    ++closedForm;
    boundRefused += m.enriched()->surelyIntact(stress) ? 0 : 1;
    EXPECT_LE((strain - point.strain).norm(), 1e-16 * point.strain.norm());
    EXPECT_LE((stress - r.stress).norm(), 1e-15 * r.stress.norm());
  }
  EXPECT_GT(closedForm, 1000);
  EXPECT_GT(boundRefused, 100);  // the cases the cheap bound alone would have sent to update()
}

TEST(TwoPhasePoint, ClosedFormSecantSolveInvertsTheSecantJacobian) {
  // secantSolve (the elastic predictor's solve, n^T a n = mu I + (lambda + mu) n n^T for an
  // isotropic a) must be the inverse of K of Eq. (9) with a_L = x a, for any normal, f and x,
  // in plane stress and plane strain.
  for (const Hypothesis hyp : {Hypothesis::PlaneStress, Hypothesis::PlaneStrain}) {
    const TwoPhasePoint model(test::paperEnriched(0.2, hyp));
    for (const double angle : {0.0, 0.3, 1.2, 2.9}) {
      for (const double f : {1e-6, 0.02, 0.5, 0.999}) {
        for (const double x : {1.0, 0.4, 1e-9}) {
          BandState b;
          b.crackNormal = Vec2(std::cos(angle), std::sin(angle));
          b.volumeFraction = f;
          const Vec2 r(0.7, -1.3);
          const Vec2 back = model.secantJacobian(b, x) * model.secantSolve(b, x, r);
          EXPECT_LE((back - r).norm(), 1e-12 * r.norm()) << angle << " " << f << " " << x;
        }
      }
    }
  }
}

TEST(TwoPhasePoint, UpdateWithoutTangentGivesTheSameStateAndStress) {
  // An explicit solver asks for no consistent tangent (UpdateOptions::tangent = false): the
  // stress, the band state and the dissipation must not depend on that choice, on a path that
  // loads, unloads (elastic predictor) and reloads the band, in tension and shear.
  TwoPhasePoint model(test::paperEnriched());
  const auto size = EffectiveSize::fixed(2.5);
  EnrichedState with, without;
  const Voigt load(4e-6, -5e-7, 2e-6);
  int unloading = 0, loading = 0;
  for (int i = 0; i < 200; ++i) {
    const Voigt d = (i % 50 < 35 ? 1.0 : -1.0) * load;
    const UpdateResult a = model.update(with, d, size);
    UpdateResult b;
    if (without.band) {
      b = model.updateCracked(*without.band, without.strain, d, UpdateOptions{SnapBackPolicy::Stop, false});
    } else {
      b = model.updateIntact(without.strain, d, size, without.band, UpdateOptions{SnapBackPolicy::Stop, false});
    }
    ASSERT_TRUE(a.converged() && b.converged()) << i;
    EXPECT_EQ(a.stress, b.stress) << i;
    EXPECT_EQ(a.dissipation, b.dissipation) << i;
    EXPECT_EQ(with.strain, without.strain) << i;
    ASSERT_EQ(with.band.has_value(), without.band.has_value());
    if (with.band) {
      EXPECT_EQ(with.band->jump, without.band->jump) << i;
      EXPECT_EQ(with.band->integrity, without.band->integrity) << i;
      (a.dissipation > 0.0 ? loading : unloading) += 1;
      EXPECT_EQ(b.tangent, Tangent::Zero()) << "no tangent was asked for";
    }
  }
  EXPECT_GT(loading, 50);    // the path exercises both branches of the update
  EXPECT_GT(unloading, 20);
}

}  // namespace
}  // namespace ecm

namespace ecm {
namespace {

// Stress locking, a property of one fixed band per point (Eqs. (2)-(6)): the band strain rate
// (n (x) [u'])^s / h of Eq. (3) has no component along the band, t.(n (x) [u'])^s t = 0, so a
// failed band (sigma_L -> 0, hence sigma n -> 0 by Eq. (6)) leaves the bulk in uniaxial stress
// along t, and by Eq. (4) the bulk takes the whole macroscopic eps_tt: d sigma_tt / d eps_tt =
// E / (1 - f), however far past f_t'. A crack that turns away from the band a point chose at
// onset is bridged by this stress (docs/den.md, "End of the run"). Expected value: E / (1 - f) with
// f = h / H = 0.05 / 2.5: 32000 / 0.98 = 32653.06 MPa.
TEST(TwoPhasePoint, AFailedBandCarriesNoTractionButLocksTheStressAlongIt) {
  test::EnrichedRun run(test::paperEnriched(), 2.5);
  ASSERT_TRUE(run.step(test::kFt / test::kE));
  for (double d = 1e-6; run.state.strain[0] < 0.5; d *= 1.1) ASSERT_TRUE(run.step(d));  // opening ~1.2 mm
  ASSERT_TRUE(run.state.band);
  EXPECT_LT(std::abs(run.stress[0]), 1e-3 * test::kFt) << "the band has failed: no traction across it";
  const Voigt before = run.stress;
  const double dEyy = 1e-4;
  for (int i = 0; i < 10; ++i) {  // eps_yy (along the band, t = (0, 1)) up to 10 x the onset strain
    const UpdateResult r = run.model.update(run.state, Voigt(0.0, dEyy, 0.0), run.size);
    ASSERT_TRUE(r.converged()) << toString(r.status);
    run.stress = r.stress;
  }
  const Voigt change = run.stress - before;
  const double f = test::kBandWidth / 2.5;
  EXPECT_NEAR(change[1] / (10 * dEyy), test::kE / (1.0 - f), 1e-9 * test::kE);
  EXPECT_LT(std::abs(run.stress[0]), 1e-3 * test::kFt);  // sigma_nn stays ~0
  EXPECT_LT(std::abs(run.stress[2]), 1e-3 * test::kFt);  // sigma_nt stays ~0
  EXPECT_GT(run.stress[1], 10.0 * test::kFt) << "the bulk carries 10 f_t' along the failed band";
}

}  // namespace
}  // namespace ecm
