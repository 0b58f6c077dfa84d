// Choosing the calibration mode and rejecting bad input with value and bound.
#include "calibration/calibration_input.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <limits>

#include "calibration/calibration_error.hpp"
#include "calibration/calibration_run.hpp"
#include "material/smeared_crack.hpp"
#include "../paper_constants.hpp"

namespace ecm::calibration {
namespace {

CalibrationInput concrete() {
  CalibrationInput in;
  in.youngsModulus = test::kE;
  in.tensileStrength = test::kFt;
  in.fractureEnergy = test::kGF;
  in.bandWidth = test::kBandWidth;
  in.softeningExponent = test::kN;
  return in;
}

// The message of the CalibrationError that planCalibration throws for `in`.
std::string rejection(const CalibrationInput& in) {
  try {
    planCalibration(in);
  } catch (const CalibrationError& e) {
    return e.what();
  }
  ADD_FAILURE() << "accepted";
  return {};
}

void expectHas(const std::string& text, const std::string& needle) {
  EXPECT_NE(text.find(needle), std::string::npos) << "'" << needle << "' not in: " << text;
}

TEST(CalibrationInput, ModesFollowFromTheGivenQuantities) {
  EXPECT_EQ(planCalibration(concrete()).mode, CalibrationMode::SolveSofteningModulus);
  CalibrationInput fit = concrete();
  fit.softeningExponent.reset();
  fit.fit = "hordijk";
  const CalibrationPlan p = planCalibration(fit);
  EXPECT_EQ(p.mode, CalibrationMode::Fit);
  ASSERT_TRUE(p.target.has_value());
  EXPECT_EQ(p.target->source, "hordijk");
  CalibrationInput forward = concrete();
  forward.fractureEnergy.reset();
  forward.softeningModulus = test::kEp;
  EXPECT_EQ(planCalibration(forward).mode, CalibrationMode::Forward);
  CalibrationInput band = concrete();
  band.bandWidth.reset();
  band.smearedSize = 100.0;
  EXPECT_EQ(planCalibration(band).mode, CalibrationMode::CrackBand);
  EXPECT_EQ(planCalibration(band).width, 100.0);
}

TEST(CalibrationInput, ExponentAtOrAboveOneHalfIsRefusedWithTheBound) {
  CalibrationInput in = concrete();
  in.softeningExponent = 0.5;
  const std::string m = rejection(in);
  expectHas(m, "softening_exponent n (--n) = 0.5");
  expectHas(m, "(0, 0.5)");
  expectHas(m, "infinite fracture energy");
}

TEST(CalibrationInput, GFBelowTheElasticMinimumIsRefused) {
  CalibrationInput in = concrete();
  in.fractureEnergy = 1e-6;
  const std::string m = rejection(in);
  expectHas(m, "fracture_energy GF (--GF) = 1e-06 N/mm");
  expectHas(m, "elastic minimum h ft^2/(2E) = 7.03125e-06 N/mm");
}

TEST(CalibrationInput, NegativeAndNaNValuesAreRefused) {
  CalibrationInput in = concrete();
  in.youngsModulus = -32000.0;
  expectHas(rejection(in), "youngs_modulus E (--E) = -32000 MPa is outside the allowed range (0, inf)");
  in = concrete();
  in.tensileStrength = std::numeric_limits<double>::quiet_NaN();
  expectHas(rejection(in), "tensile_strength ft (--ft) = nan is not a finite number");
  in = concrete();
  in.bandWidth = 0.0;
  expectHas(rejection(in), "band_width h (--h) = 0 mm");
  in = concrete();
  in.fractureEnergy = -0.11;
  expectHas(rejection(in), "fracture_energy GF (--GF) = -0.11 N/mm is outside");
}

TEST(CalibrationInput, MissingAndConflictingQuantities) {
  CalibrationInput in = concrete();
  in.tensileStrength.reset();
  expectHas(rejection(in), "missing tensile_strength ft (--ft)");
  in = concrete();
  in.softeningModulus = 8.0;
  expectHas(rejection(in), "softening_modulus Ep (--Ep) cannot be given together with fracture_energy");
  in = concrete();
  in.fit = "hordijk";
  expectHas(rejection(in), "softening_exponent n (--n) is determined by the fit");
  in = concrete();
  in.smearedSize = 100.0;
  expectHas(rejection(in), "band_width h (--h) is not used by the crack-band calibration");
  expectHas(rejection(CalibrationInput{}), "nothing to calibrate");
  in = concrete();
  in.writeMaterial = "m.yaml";
  expectHas(rejection(in), "missing poisson_ratio nu (--nu), needed for --write-material");
}

TEST(CalibrationInput, CrackBandBeyondTheCriticalSizeIsRefused) {
  CalibrationInput in = concrete();
  in.bandWidth.reset();
  in.smearedSize = 800.0;
  const CalibrationPlan p = planCalibration(in);
  try {
    runCalibration(p);
    FAIL() << "calibrated beyond H_crit";
  } catch (const RegularisationError& e) {
    EXPECT_NEAR(e.criticalSize, 782.2222, 1e-3);
    EXPECT_NEAR(e.requiredStrength, std::sqrt(2.0 * test::kE * test::kGF / 800.0), 1e-12);
  }
  in.smearedSize = 100.0;
  const CalibrationResult r = runCalibration(planCalibration(in));
  EXPECT_LE(std::abs(r.relativeError), 1e-8);
  EXPECT_NEAR(r.criticalSize, 782.2222, 1e-3);
}

std::filesystem::path writeYaml(const std::string& name, const std::string& text) {
  const auto path = std::filesystem::temp_directory_path() / ("ecm-calibration-input-" + name);
  std::ofstream(path) << text;
  return path;
}

TEST(CalibrationInput, YamlValuesAreCheckedAtTheirLine) {
  const auto path = writeYaml("bad.yaml",
                              "# units: mm, N, MPa\n"
                              "youngs_modulus: 32000\n"
                              "tensile_strength: 3.0\n"
                              "fracture_energy: 0.11\n"
                              "band_width: 0.05\n"
                              "softening_exponent: 0.7\n");
  const CalibrationInput in = readCalibrationInput(path);
  try {
    planCalibration(in);
    FAIL();
  } catch (const io::InputError& e) {
    EXPECT_EQ(e.file, path.string());
    EXPECT_EQ(e.line, 6);
    expectHas(e.what(), "key 'softening_exponent' (n) = 0.7 is outside the allowed range (0, 0.5)");
  }
  // The command line overrides the file (and its origin).
  CalibrationInput fixed = in;
  CalibrationInput cli;
  cli.softeningExponent = test::kN;
  overlay(fixed, cli);
  EXPECT_EQ(planCalibration(fixed).law.softeningExponent, test::kN);
  std::filesystem::remove(path);
}

TEST(CalibrationInput, YamlUnknownKeysAndTypesAreRefused) {
  const auto unknown = writeYaml("unknown.yaml", "youngs_modulus: 32000\nyoung_modulus: 1\n");
  try {
    readCalibrationInput(unknown);
    FAIL();
  } catch (const io::InputError& e) {
    EXPECT_EQ(e.line, 2);
    expectHas(e.what(), "unknown key 'young_modulus'");
  }
  const auto text = writeYaml("text.yaml", "youngs_modulus: 32000\nfracture_energy: lots\n");
  try {
    readCalibrationInput(text);
    FAIL();
  } catch (const io::InputError& e) {
    EXPECT_EQ(e.line, 2);
    expectHas(e.what(), "key 'fracture_energy': expected a number");
  }
  std::filesystem::remove(unknown);
  std::filesystem::remove(text);
}

}  // namespace
}  // namespace ecm::calibration
