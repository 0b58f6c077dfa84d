// The band's fracture energy G_F = h int F dD and the E_p that gives a prescribed G_F.
#include "calibration/fracture_energy.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "calibration/calibration_error.hpp"
#include "../paper_constants.hpp"

namespace ecm::calibration {
namespace {

TEST(FractureEnergy, PaperConcreteSolvesToEp818) {
  const SofteningModulusSolution s = solveSofteningModulus(test::concreteShape(), test::kGF, test::kBandWidth);
  EXPECT_NEAR(s.softeningModulus, 8.18, 0.02);
  EXPECT_LE(std::abs(s.relativeError), 1e-8);
  EXPECT_LE(std::abs(s.fractureEnergy / test::kGF - 1.0), 1e-8);
  // The reported error is the real one: recompute forward.
  DamageLawParams law = test::concreteShape();
  law.softeningModulus = s.softeningModulus;
  EXPECT_LE(std::abs(fractureEnergy(law, test::kBandWidth) / test::kGF - 1.0), 1e-8);
}

TEST(FractureEnergy, PaperConcreteForwardGives011) {
  const double gf = fractureEnergy({test::kE, test::kFt, test::kEp, test::kN}, test::kBandWidth);
  EXPECT_NEAR(gf, 0.110, 0.001 * 0.110);
}

// Independent check of G_F: the work of the uniaxial stress on the band strain to complete
// failure, W = int sigma d eps_L, equals the dissipation int_0^1 F dD because the stored energy
// sigma eps_L / 2 ~ x^(1-2n) vanishes at failure (energy balance of Eqs. (11)-(13)). Pre-peak the
// band is elastic (W = f_t'^2/(2E)); post-peak, along x from 1 to 0,
//   sigma = uniaxialStress(x),  eps_L = sigma / (x E),  d eps_L/dx = F'(x) / (E eps_L),
// with F' = damageFunctionSlope. Composite Simpson in u with x = u^8 (graded towards x = 0, where
// the integrand grows like x^(-2n)). This uses neither dissipationToFailure nor any F(D) code of
// the calibration library.
double bandWorkToFailure(const DamageLawParams& law) {
  const double e = law.youngsModulus;
  const auto integrand = [&](double u) {
    if (u <= 0.0) return 0.0;  // g(x) dx/du ~ u^(8(1 - 2n) - 1) -> 0
    const double x = std::pow(u, 8.0);
    const double sigma = uniaxialStress(law, x);
    const double epsL = sigma / (x * e);
    const double depsLdx = damageFunctionSlope(law, x) / (e * epsL);
    return -sigma * depsLdx * 8.0 * std::pow(u, 7.0);
  };
  constexpr int intervals = 40000;  // even
  const double du = 1.0 / intervals;
  double sum = integrand(0.0) + integrand(1.0);
  for (int i = 1; i < intervals; ++i) sum += (i % 2 ? 4.0 : 2.0) * integrand(i * du);
  const double elastic = law.tensileStrength * law.tensileStrength / (2.0 * e);
  return elastic + sum * du / 3.0;
}

TEST(FractureEnergy, RvePhasesOfTable1MatchAnIndependentIntegration) {
  for (const test::RvePhase& ph : test::kRvePhases) {
    SCOPED_TRACE(ph.name);
    const DamageLawParams law{ph.youngsModulus, ph.tensileStrength, ph.softeningModulus, test::kRveExponent};
    const double gf = fractureEnergy(law, test::kRveBandWidth);
    const double independent = test::kRveBandWidth * bandWorkToFailure(law);
    EXPECT_NEAR(gf, independent, 1e-10 * independent);
    // Solving back from this G_F recovers Table 1's E_p.
    const SofteningModulusSolution s = solveSofteningModulus(law, gf, test::kRveBandWidth);
    EXPECT_NEAR(s.softeningModulus, ph.softeningModulus, 1e-7 * ph.softeningModulus);
  }
}

TEST(FractureEnergy, IndependentIntegrationAlsoAgreesForTheConcrete) {
  const DamageLawParams law{test::kE, test::kFt, test::kEp, test::kN};
  EXPECT_NEAR(fractureEnergy(law, test::kBandWidth), test::kBandWidth * bandWorkToFailure(law), 1e-10 * test::kGF);
}

TEST(FractureEnergy, GFBelowTheElasticMinimumIsRefused) {
  const double least = minimumFractureEnergy(test::kE, test::kFt, test::kBandWidth);
  EXPECT_DOUBLE_EQ(least, test::kBandWidth * test::kFt * test::kFt / (2.0 * test::kE));
  try {
    solveSofteningModulus(test::concreteShape(), 0.5 * least, test::kBandWidth);
    FAIL() << "no error";
  } catch (const CalibrationError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("elastic minimum"), std::string::npos) << what;
    EXPECT_NE(what.find("7.03125e-06"), std::string::npos) << what;  // the bound
    EXPECT_NE(what.find("3.515625e-06"), std::string::npos) << what; // the value
  }
  // Just above the minimum a (very stiff) E_p still exists.
  const SofteningModulusSolution s = solveSofteningModulus(test::concreteShape(), 1.5 * least, test::kBandWidth);
  EXPECT_GT(s.softeningModulus, test::kE);
  EXPECT_LE(std::abs(s.relativeError), 1e-8);
}

TEST(FractureEnergy, OutOfRangeShapesAreRefused) {
  EXPECT_THROW(solveSofteningModulus(test::concreteShape(0.5), test::kGF, test::kBandWidth), CalibrationError);
  EXPECT_THROW(solveSofteningModulus(test::concreteShape(-0.1), test::kGF, test::kBandWidth), CalibrationError);
  EXPECT_THROW(solveSofteningModulus(test::concreteShape(), -0.11, test::kBandWidth), CalibrationError);
  EXPECT_THROW(solveSofteningModulus(test::concreteShape(), std::numeric_limits<double>::quiet_NaN(), test::kBandWidth),
               CalibrationError);
  EXPECT_THROW(solveSofteningModulus({-1.0, test::kFt, 0.0, test::kN}, test::kGF, test::kBandWidth), CalibrationError);
}

}  // namespace
}  // namespace ecm::calibration
