// The damage function F(D) of Eq. (13) and the quantities derived from it.
#include "material/damage_function.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "../paper_constants.hpp"

namespace ecm {
namespace {

const DamageLawParams kLaw{test::kE, test::kFt, test::kEp, test::kN};

TEST(DamageFunction, StartsAtTheElasticEnergyAtPeak) {
  // Eq. (13) at D = 0: F = f_t'^2 / (2E) = 9 / 64000.
  EXPECT_DOUBLE_EQ(damageFunction(kLaw, 1.0), 9.0 / 64000.0);
}

TEST(DamageFunction, SlopeMatchesFiniteDifferences) {
  for (double x : {1.0 - 1e-9, 0.9, 0.5, 1e-2, 1e-4, 1e-8}) {
    const double dx = 1e-6 * x;
    const double fd = (damageFunction(kLaw, x + dx) - damageFunction(kLaw, x - dx)) / (2 * dx);
    EXPECT_NEAR(damageFunctionSlope(kLaw, x), fd, 1e-7 * std::abs(fd)) << "x = " << x;
  }
}

TEST(DamageFunction, InitialSofteningSlopeOfTheUniaxialLawIsMinusEp) {
  // docs/model.md, identities: d sigma / d eps_L = -E_p at the peak, with sigma = x E eps, Y = E eps^2 / 2 = F(x).
  const double dx = 1e-7;
  const double x = 1.0 - dx;
  const double epsPeak = test::kFt / test::kE;
  const double eps = std::sqrt(2.0 * damageFunction(kLaw, x) / test::kE);
  const double slope = (uniaxialStress(kLaw, x) - test::kFt) / (eps - epsPeak);
  EXPECT_NEAR(slope, -test::kEp, 1e-4 * test::kEp);
}

TEST(DamageFunction, IntegritySolveInvertsF) {
  for (double x : {0.999999, 0.7, 0.1, 1e-3, 1e-6, 1e-9, 1e-13}) {
    const double y = damageFunction(kLaw, x);
    EXPECT_NEAR(integrityForDrivingForce(kLaw, y), x, 1e-10 * x) << "x = " << x;
  }
}

TEST(DamageFunction, IntegritySolveIsIrreversibleAndBounded) {
  const double x0 = 0.3;
  EXPECT_EQ(integrityForDrivingForce(kLaw, 0.0, x0), x0);  // no driving force: no change
  EXPECT_EQ(integrityForDrivingForce(kLaw, damageFunction(kLaw, 0.5), x0), x0);  // below threshold
  for (double y : {1e3, 1e8, 1e15, 1e30}) {  // enormous driving forces: x stays in (0, 1), finite
    const double x = integrityForDrivingForce(kLaw, y);
    EXPECT_TRUE(std::isfinite(x));
    EXPECT_GE(x, 0.0);
    EXPECT_LT(x, 1.0);
  }
}

TEST(DamageFunction, HugeDrivingForcesGiveTheSameIntegrityFromEveryStart) {
  // A huge increment at D near 1 (found by fuzz/fuzz_point_scene.cpp: a strain of 4e22 in one
  // increment gave an integrity of -4e-121 and a NaN dissipation). Eq. (13) at the root, with
  // r = sqrt(2 E Y) / f_t' and s = x^n: E = r E x + (r - 1) E_p s. Once E x << E_p s there the
  // root is s = E / ((r - 1) E_p) to round-off, whatever the integrity the solve starts from.
  for (double strain : {1e10, 1e20, 1e22, 4e22, 1e24}) {
    const double sigma = kLaw.youngsModulus * strain;
    const double y = sigma * sigma / (2.0 * kLaw.youngsModulus);
    const double r = strain * kLaw.youngsModulus / kLaw.tensileStrength;
    const double s = kLaw.youngsModulus / ((r - 1.0) * kLaw.softeningModulus);
    for (double x0 : {1.0, 0.0072, 1e-30}) {
      const PoweredIntegrity x = solveIntegrity(kLaw, y, PoweredIntegrity{x0, std::pow(x0, kLaw.softeningExponent)});
      EXPECT_NEAR(x.xn, s, 1e-12 * s) << "strain " << strain << ", start " << x0;
      EXPECT_NEAR(x.x, std::pow(s, 1.0 / kLaw.softeningExponent), 1e-11 * x.x) << "strain " << strain << ", start " << x0;
      EXPECT_GT(x.x, 0.0);
      EXPECT_TRUE(std::isfinite(dissipationBetween(kLaw, x0, x.x)));
    }
  }
}

TEST(DamageFunction, PaperConcreteDissipatesTheFractureEnergy) {
  // The paper's verified erratum, G_F = 0.11 N/mm (docs/model.md): h int_0^1 F dD = 0.1100 N/mm
  // for the paper's concrete.
  EXPECT_NEAR(test::kBandWidth * dissipationToFailure(kLaw), 0.110, 0.0005 * 0.110);
}

TEST(DamageFunction, IncrementalDissipationAddsUpToTheTotal) {
  // Sum of int F dD over a partition of (0, 1] equals the adaptive GSL quadrature of the whole.
  double sum = 0.0, x = 1.0;
  while (x > 1e-30) {
    const double next = x * 0.7;
    sum += dissipationBetween(kLaw, x, next);
    x = next;
  }
  sum += dissipationBetween(kLaw, x, 0.0);
  EXPECT_NEAR(sum, dissipationToFailure(kLaw), 1e-9 * sum);
  // ... and over fine partitions (every increment < 5 %: 3-point Gauss in x, the per-increment
  // rule of ordinary updates; 0.951 is its widest case), 1e-10.
  for (const double ratio : {0.99, 0.951}) {
    double fine = 0.0;
    for (x = 1.0; x > 1e-30; x *= ratio) fine += dissipationBetween(kLaw, x, ratio * x);
    EXPECT_NEAR(fine, dissipationToFailure(kLaw), 1e-10 * fine) << ratio;
  }
}

TEST(DamageFunction, SimpsonWithKnownEndsMatchesTheGaussRule) {
  // The loading update knows F at both ends (threshold and Y) and uses Simpson's rule below a
  // 0.1 % change of x: against the 3-point Gauss rule (exact to ~1e-16 there), the error of
  // Simpson's rule falls as (dx/x)^4: measured 2.6e-11 relative at 0.5 %, 4e-14 at 0.1 %.
  for (const double x : {1.0, 0.5, 1e-3, 1e-9}) {
    for (const double ratio : {0.999999, 0.9999, 0.99901}) {
      const double gauss = dissipationBetween(kLaw, x, ratio * x);
      const double simpson = dissipationBetween(kLaw, x, ratio * x, damageFunction(kLaw, x), damageFunction(kLaw, ratio * x));
      EXPECT_NEAR(simpson, gauss, 1e-12 * gauss) << "x = " << x << ", ratio " << ratio;
    }
    // A wider increment ignores the ends and takes the panel quadrature.
    EXPECT_EQ(dissipationBetween(kLaw, x, 0.5 * x, 0.0, 0.0), dissipationBetween(kLaw, x, 0.5 * x));
  }
  EXPECT_EQ(dissipationBetween(kLaw, 0.5, 0.5, 1.0, 1.0), 0.0);  // no damage growth, nothing dissipated
}

TEST(DamageFunction, GivenPowerGivesTheSameF) {
  for (const double x : {1.0, 0.3, 1e-7}) EXPECT_EQ(damageFunction(kLaw, x, std::pow(x, test::kN)), damageFunction(kLaw, x));
}

TEST(DamageFunction, SubnormalIntegritiesEndTheQuadrature) {
  // Fuzzer finding (fuzz/corpus/material_update/subnormal-integrity): from a subnormal x the
  // panels were cut by 1.2 forever (4.9e-324 / 1.2 rounds back to 4.9e-324). Now they stop at
  // the smallest normal double (the integral below it, ~x^(1-2n), is ~1e-240).
  for (const double xOld : {1.4821969375237396e-323, 4.9406564584124654e-324, 1e-310}) {
    const double w = dissipationBetween(kLaw, xOld, 0.0);
    EXPECT_TRUE(std::isfinite(w)) << xOld;
    EXPECT_GE(w, 0.0) << xOld;
    EXPECT_LT(w, 1e-200) << xOld;  // int_0^x F dx ~ x^(1-2n) ~ 1e-240 here
  }
}

TEST(DamageFunction, OneIncrementToFailureDissipatesTheWholeIntegral) {
  // A single huge increment (x: 1 -> 1e-15, then the rest) against GSL's adaptive quadrature.
  const double twoSteps = dissipationBetween(kLaw, 1.0, 1e-15) + dissipationBetween(kLaw, 1e-15, 0.0);
  EXPECT_NEAR(twoSteps, dissipationToFailure(kLaw), 1e-9 * dissipationToFailure(kLaw));
  EXPECT_NEAR(dissipationBetween(kLaw, 1.0, 0.0), dissipationToFailure(kLaw), 1e-9 * dissipationToFailure(kLaw));
}

TEST(DamageFunction, FractureEnergyFollowsTheClosedFormWhenEpVanishesFromTheTail) {
  // Independent check: as n -> 0 the law approaches F = k [(E + Ep)/(E x + Ep)]^2, whose
  // integral is k (E + Ep) / Ep in closed form (int_0^1 dx/(Ex + Ep)^2 = 1/(Ep (E + Ep))).
  const DamageLawParams law{1000.0, 2.0, 50.0, 1e-9};
  const double k = 4.0 / 2000.0;
  EXPECT_NEAR(dissipationToFailure(law), k * 1050.0 / 50.0, 1e-6);
}

}  // namespace
}  // namespace ecm
