// The traction-opening curve of the law in uniaxial tension.
#include "calibration/softening_curve.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "calibration/fracture_energy.hpp"
#include "../paper_constants.hpp"

namespace ecm::calibration {
namespace {

const DamageLawParams kLaw{test::kE, test::kFt, test::kEp, test::kN};

TEST(SofteningCurve, PointFollowsTheDefinitions) {
  const SofteningCurve c(kLaw, test::kBandWidth);
  const double x = 0.01;
  const SofteningPoint p = c.at(x);
  EXPECT_DOUBLE_EQ(p.stress, uniaxialStress(kLaw, x));
  EXPECT_DOUBLE_EQ(p.bandStrain, p.stress / (x * test::kE));
  EXPECT_DOUBLE_EQ(p.opening, test::kBandWidth * (p.bandStrain - p.stress / test::kE));
  EXPECT_DOUBLE_EQ(p.damage, 0.99);
  const SofteningPoint peak = c.at(1.0);
  EXPECT_DOUBLE_EQ(peak.stress, test::kFt);
  EXPECT_DOUBLE_EQ(peak.opening, 0.0);
  EXPECT_DOUBLE_EQ(c.peakStress(), test::kFt);
}

TEST(SofteningCurve, StressFallsAndOpeningGrowsMonotonically) {
  const SofteningCurve c(kLaw, test::kBandWidth);
  SofteningPoint prev = c.at(1.0);
  for (int i = 1; i <= 3000; ++i) {
    const SofteningPoint p = c.at(std::pow(10.0, -15.0 * i / 3000.0));
    ASSERT_LT(p.stress, prev.stress) << i;
    ASSERT_GT(p.opening, prev.opening) << i;
    prev = p;
  }
}

TEST(SofteningCurve, InversionsAreExact) {
  const SofteningCurve c(kLaw, test::kBandWidth);
  for (double w : {1e-5, 1e-3, 0.02, 0.1, 0.5}) {
    EXPECT_NEAR(c.atOpening(w).opening, w, 1e-11 * w);
  }
  for (double f : {0.9, 0.5, 0.1, 0.01}) {
    const double w = c.openingAtStressFraction(f);
    EXPECT_NEAR(c.atOpening(w).stress, f * test::kFt, 1e-10 * test::kFt);
  }
  const std::vector<double> w = {0.0, 0.01, 0.01, 0.05, 0.2};
  const std::vector<double> s = c.stressesAtOpenings(w);
  for (std::size_t i = 0; i < w.size(); ++i) EXPECT_NEAR(s[i], c.atOpening(w[i]).stress, 1e-10 * test::kFt) << i;
}

TEST(SofteningCurve, AreaUnderTheCurveIsTheFractureEnergy) {
  // int_0^inf sigma dw = G_F (the definition of the opening); trapezoids on a fine grid plus the
  // tail beyond w_max, where sigma ~ w^(-(1-n)/n) decays fast.
  const SofteningCurve c(kLaw, test::kBandWidth);
  const std::vector<SofteningPoint> pts = c.sample(3.0, 60001);
  double area = 0.0;
  for (std::size_t i = 1; i < pts.size(); ++i)
    area += 0.5 * (pts[i].stress + pts[i - 1].stress) * (pts[i].opening - pts[i - 1].opening);
  EXPECT_NEAR(area, fractureEnergy(kLaw, test::kBandWidth), 2e-4 * test::kGF);
}

}  // namespace
}  // namespace ecm::calibration
