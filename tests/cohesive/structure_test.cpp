// The notched beam and the DEN panel in tension on meshes that run in seconds: the issue's
// measurements, the energy balance and the mesh convergence of the beam's peak.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <tuple>

#include "cohesive/report.hpp"
#include "cohesive/scene.hpp"
#include "cohesive/solver.hpp"
#include "test_scenes.hpp"

namespace ecm::cohesive {
namespace {

const std::filesystem::path kReference = std::filesystem::path(ECM_SOURCE_DIR) / "data/reference";

using test::Curve;

Curve compute(const std::string& file, double cell, double maxStep, double finalControl) {
  Scene s = readScene(kReference / file, {cell, std::nullopt});
  if (maxStep > 0.0) s.solver.maxStep = s.solver.firstStep = maxStep;
  if (finalControl > 0.0) s.solver.finalControl = finalControl;
  return test::curveOf(s);
}

// Each run once per test program (two tests share the 1.25 mm beam).
Curve run(const std::string& file, double cell, double maxStep = 0.0, double finalControl = 0.0) {
  static std::map<std::tuple<std::string, double, double, double>, Curve> done;
  const auto key = std::make_tuple(file, cell, maxStep, finalControl);
  if (!done.contains(key)) done[key] = compute(file, cell, maxStep, finalControl);
  return done[key];
}

// The issue's measurement with an independent cohesive model, plane-stress Q4, nodal interface
// (mesh-converged from 2.5 to 0.3125 mm): Hordijk's law, single-node supports and load: peak
// 1175 N (at CMOD 0.036), 812 N at CMOD 0.1 mm, 459 N at 0.2 mm. Here at 1.25 mm (measured
// 2026-12-06: 1176.4 / 819.1 / 462.5; 0.625 mm: 1174.6 / 812.2 / 459.9).
TEST(CohesiveBeam, HordijkSingleNodesMatchesTheIssuesIndependentModel) {
  const Curve c = run("beam-hordijk-node.yaml", 1.25, 5e-4);
  EXPECT_NEAR(c.peak, 1175.0, 0.015 * 1175.0);
  EXPECT_NEAR(c.at01, 812.0, 0.015 * 812.0);
  EXPECT_NEAR(c.at02, 459.0, 0.015 * 459.0);
}

// The same source: ecm's band law fitted to Hordijk's curve (ecm-calibrate --fit hordijk),
// single nodes: 1135 / 821 / 425 N. Here at 1.25 mm (measured 1137.3 / 827.6 / 427.3).
TEST(CohesiveBeam, FittedBandLawSingleNodesMatchesTheIssuesIndependentModel) {
  const Curve c = run("beam-band-node.yaml", 1.25, 5e-4);
  EXPECT_NEAR(c.peak, 1135.0, 0.015 * 1135.0);
  EXPECT_NEAR(c.at01, 821.0, 0.015 * 821.0);
  EXPECT_NEAR(c.at02, 425.0, 0.015 * 425.0);
}

// The external work (trapezoidal in the load-point displacement) against bulk + interface energy
// + dissipation at the scene's default steps (max CMOD step 0.0002 mm), coarse beam: the issue
// asks 3e-6 of the work. Measured 2026-12-06 at 2.5 mm: 1.7e-6 (Hordijk), 1.1e-6 (band); the
// error halves to quarters with the step (0.001 mm: 3.3e-5, 0.0005: 1.1e-5, 0.0001: 4.9e-7).
TEST(CohesiveBeam, EnergyBalancesToThreeMillionthsOfTheWorkAtTheDefaultSteps) {
  EXPECT_LT(run("beam-hordijk-node.yaml", 2.5).finalBalance, 3e-6);
  EXPECT_LT(run("beam-band-node.yaml", 2.5).finalBalance, 3e-6);
  // And it is the step that sets it: five times the step, over ten times the error.
  EXPECT_GT(run("beam-hordijk-node.yaml", 2.5, 1e-3).finalBalance, 1e-5);
}

// The beam's peak from 2.5 to 1.25 mm changes by 0.47 % (Hordijk, single nodes: 1181.9 -> 1176.4 N,
// measured 2026-12-06; 0.15 % more to 0.625 mm).
TEST(CohesiveBeam, PeakConvergesWithTheMesh) {
  const double coarse = run("beam-hordijk-node.yaml", 2.5, 5e-4).peak;
  const double fine = run("beam-hordijk-node.yaml", 1.25, 5e-4).peak;
  EXPECT_LT(std::abs(coarse / fine - 1.0), 0.01);
  EXPECT_GT(coarse, fine);  // the coarse mesh is the stiffer one
}

// The DEN panel in pure tension. The issue's measurement (an independent cohesive model): peak
// 20.55 kN, 0.913 f_t' A (A = 150 x 50 mm^2). It is reproduced by Hordijk's curve (20.54 kN here
// at 2.5 mm, measured 2026-12-06); the paper's band law (E_p 8.184, n 0.128), whose damage mostly
// happens near f_t' (calibration/README.md), peaks higher: 21.27 kN at 2.5, 1.25 and 0.625 mm
// (this model's own converged value, docs/cohesive.md).
TEST(CohesiveDenTension, PeakMatchesTheIssuesIndependentModel) {
  const Curve hordijk = run("den-tension-hordijk.yaml", 2.5, 5e-4, 0.03);
  EXPECT_NEAR(hordijk.peak, 20550.0, 0.015 * 20550.0);
  const Curve band = run("den-tension-band.yaml", 2.5, 5e-4, 0.03);
  EXPECT_NEAR(band.peak, 21268.0, 0.005 * 21268.0);
}

}  // namespace
}  // namespace ecm::cohesive
