// The smeared crack (crack band) model and its regularisation.
#include "material/smeared_crack.hpp"

#include <gtest/gtest.h>

#include "../paper_constants.hpp"
#include "uniaxial.hpp"

namespace ecm {
namespace {

double dissipationPerVolume(const SmearedCrack& model) {
  // Uniaxial stress to complete failure; returns sum of the increments' dissipation.
  SmearedCrack::State s;
  double total = 0.0;
  const test::TrialUpdate trial = [&](const Voigt& d, bool commit) {
    SmearedCrack::State copy = s;
    const UpdateResult r = model.update(copy, d);
    if (commit) s = copy, total += r.dissipation;
    return r;
  };
  double d = test::kFt / test::kE;
  while (s.strain[0] < 5.0) {
    EXPECT_TRUE(test::uniaxialStressStep(trial, d, model.law().stiffness(), 1e-12));
    d = std::max(1e-7, 0.02 * s.strain[0]);
  }
  return total;
}

TEST(SmearedCrack, RegularisedModelDissipatesFractureEnergyPerElementSize) {
  // Crack band: E_p chosen so that int F dD = G_F / H; then H x dissipation = G_F.
  for (double bigH : {1.0, 10.0, 100.0, 500.0}) {
    DamageLawParams shape{test::kE, test::kFt, 1.0, test::kN};
    const double ep = regularisedSofteningModulus(shape, test::kGF, bigH);
    shape.softeningModulus = ep;
    EXPECT_NEAR(dissipationToFailure(shape) * bigH, test::kGF, 1e-10 * test::kGF);
    SmearedCrack model({{test::kE, test::kNu, Hypothesis::PlaneStress}, test::kFt, ep, test::kN});
    EXPECT_NEAR(bigH * dissipationPerVolume(model), test::kGF, 0.01 * test::kGF) << "H = " << bigH;
  }
}

TEST(SmearedCrack, UnregularisedModelDissipatesTheBandEnergyPerVolume) {
  // With the band's own E_p the dissipation per volume is int F dD, independent of H: the
  // structural energy then scales with the element size (the mesh dependence of the paper).
  SmearedCrack model(test::paperBand());
  const double perVolume = dissipationToFailure({test::kE, test::kFt, test::kEp, test::kN});
  EXPECT_NEAR(dissipationPerVolume(model), perVolume, 0.01 * perVolume);
}

TEST(SmearedCrack, NoRegularisationBeyondTheCriticalSize) {
  // docs/model.md, identities: H_crit = 2 E G_F / f_t'^2 = 782.2 mm for the paper's concrete.
  EXPECT_NEAR(criticalSmearedSize(test::kE, test::kFt, test::kGF), 782.2222, 1e-3);
  try {
    regularisedSofteningModulus({test::kE, test::kFt, 1.0, test::kN}, test::kGF, 800.0);
    FAIL() << "regularised beyond H_crit";
  } catch (const RegularisationError& e) {
    EXPECT_NEAR(e.criticalSize, 782.2222, 1e-3);
    EXPECT_NEAR(e.requiredStrength, std::sqrt(2.0 * test::kE * test::kGF / 800.0), 1e-12);
  }
}

}  // namespace
}  // namespace ecm
