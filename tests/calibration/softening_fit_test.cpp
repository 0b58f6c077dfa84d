// Fitting (E_p, n) to a softening curve at fixed G_F.
#include "calibration/softening_fit.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "calibration/calibration_error.hpp"
#include "calibration/fracture_energy.hpp"
#include "calibration/softening_curve.hpp"
#include "calibration/target_csv.hpp"
#include "io/yaml_input.hpp"
#include "../paper_constants.hpp"

namespace ecm::calibration {
namespace {

TEST(Hordijk, CurveHasItsKnownShape) {
  const double wc = hordijkCriticalOpening(test::kFt, test::kGF);
  EXPECT_DOUBLE_EQ(wc, 5.14 * test::kGF / test::kFt);
  EXPECT_DOUBLE_EQ(hordijkStress(0.0, test::kFt, test::kGF), test::kFt);
  EXPECT_NEAR(hordijkStress(wc, test::kFt, test::kGF), 0.0, 1e-15);
  EXPECT_EQ(hordijkStress(2.0 * wc, test::kFt, test::kGF), 0.0);
  // Its area is G_F (to the ~0.1% of the rounded constants 5.14, 6.93).
  double area = 0.0;
  constexpr int n = 20000;
  for (int i = 0; i < n; ++i) {
    const double a = wc * i / n, b = wc * (i + 1) / n;
    area += 0.5 * (b - a) * (hordijkStress(a, test::kFt, test::kGF) + hordijkStress(b, test::kFt, test::kGF));
  }
  EXPECT_NEAR(area, test::kGF, 2e-3 * test::kGF);
}

TEST(SofteningFit, HordijkFitKeepsGFExactlyWithASmallResidual) {
  const TargetCurve target = hordijkCurve(test::kFt, test::kGF);
  const FitResult f = fitSoftening(test::concreteShape(), test::kGF, test::kBandWidth, target);
  EXPECT_LE(std::abs(f.relativeError), 1e-8);
  EXPECT_FALSE(f.atBound);
  EXPECT_GT(f.softeningExponent, 0.0);
  EXPECT_LT(f.softeningExponent, 0.5);
  EXPECT_LT(f.residual, 0.03);
  // The fitted law does dissipate G_F.
  DamageLawParams law = test::concreteShape(f.softeningExponent);
  law.softeningModulus = f.softeningModulus;
  EXPECT_LE(std::abs(fractureEnergy(law, test::kBandWidth) / test::kGF - 1.0), 1e-8);
  EXPECT_DOUBLE_EQ(fitResidual(law, test::kBandWidth, target), f.residual);
  // A minimum: both neighbours in n (each with its own E_p from G_F) fit worse, and so does the
  // paper's n = 0.128.
  for (double dn : {-0.01, 0.01}) {
    DamageLawParams other = test::concreteShape(f.softeningExponent + dn);
    other.softeningModulus = solveSofteningModulus(other, test::kGF, test::kBandWidth).softeningModulus;
    EXPECT_GT(fitResidual(other, test::kBandWidth, target), f.residual) << dn;
  }
  EXPECT_GT(fitResidual({test::kE, test::kFt, test::kEp, test::kN}, test::kBandWidth, target), f.residual);
}

TEST(SofteningFit, RecoversTheLawThatMadeTheTarget) {
  // Points sampled from a law of the model's own form: the fit finds its n and E_p again.
  DamageLawParams law = test::concreteShape(0.2);
  law.softeningModulus = solveSofteningModulus(law, test::kGF, test::kBandWidth).softeningModulus;
  const SofteningCurve curve(law, test::kBandWidth);
  TargetCurve target;
  target.source = "synthetic";
  for (int i = 1; i <= 40; ++i) {
    target.opening.push_back(0.005 * i);
    target.stress.push_back(curve.atOpening(0.005 * i).stress);
  }
  const FitResult f = fitSoftening(test::concreteShape(), test::kGF, test::kBandWidth, target);
  EXPECT_NEAR(f.softeningExponent, 0.2, 1e-5);
  EXPECT_NEAR(f.softeningModulus, law.softeningModulus, 1e-4 * law.softeningModulus);
  EXPECT_LT(f.residual, 1e-6);
}

TEST(SofteningFit, TargetsNeedThreeIncreasingPoints) {
  TargetCurve t{"code", {0.01, 0.02}, {2.0, 1.0}};
  EXPECT_THROW(fitSoftening(test::concreteShape(), test::kGF, test::kBandWidth, t), CalibrationError);
  t = {"code", {0.01, 0.03, 0.02}, {2.0, 1.0, 0.5}};
  EXPECT_THROW(fitSoftening(test::concreteShape(), test::kGF, test::kBandWidth, t), CalibrationError);
}

std::filesystem::path writeCsv(const std::string& name, const std::string& text) {
  const auto path = std::filesystem::temp_directory_path() / ("ecm-calibration-test-" + name);
  std::ofstream(path) << text;
  return path;
}

TEST(SofteningFit, CsvTargetsAreCheckedWithFileAndLine) {
  const auto good = writeCsv("good.csv", "# w (mm), sigma (MPa)\nw,sigma\n0.0,3.0\n0.02,1.5\n0.05,0.6\n");
  const TargetCurve t = readTargetCsv(good);
  EXPECT_EQ(t.opening.size(), 3u);
  EXPECT_EQ(t.stress[1], 1.5);

  const auto two = writeCsv("two.csv", "w,sigma\n0.0,3.0\n0.02,1.5\n");
  try {
    readTargetCsv(two);
    FAIL();
  } catch (const io::InputError& e) {
    EXPECT_EQ(e.line, 3);
    EXPECT_NE(std::string(e.what()).find("at least 3"), std::string::npos) << e.what();
  }
  const auto back = writeCsv("back.csv", "w,sigma\n0.0,3.0\n0.02,1.5\n0.01,0.6\n");
  try {
    readTargetCsv(back);
    FAIL();
  } catch (const io::InputError& e) {
    EXPECT_EQ(e.line, 4);
    EXPECT_NE(std::string(e.what()).find("w = 0.01 mm after w = 0.02 mm"), std::string::npos) << e.what();
  }
  const auto negative = writeCsv("neg.csv", "-0.01,3.0\n0.02,1.5\n0.03,0.6\n");
  EXPECT_THROW(readTargetCsv(negative), io::InputError);
  for (const auto& p : {good, two, back, negative}) std::filesystem::remove(p);
}

}  // namespace
}  // namespace ecm::calibration
