// One material, two independent computations: the calibration's quadrature fixes E_p for
// G_F; the point driver, running the enriched model on that material to complete failure,
// must dissipate the same G_F (within 0.5%).
#include <gtest/gtest.h>

#include "calibration/fracture_energy.hpp"
#include "../paper_constants.hpp"
#include "driver/point_driver.hpp"

namespace ecm {
namespace {

TEST(CalibratedMaterial, PointDriverDissipatesTheCalibratedFractureEnergy) {
  // The paper's concrete (tests/paper_constants.hpp), E_p solved for G_F = 0.11 N/mm.
  const auto solved = calibration::solveSofteningModulus(test::concreteShape(), test::kGF, test::kBandWidth);
  for (double bigH : {2.5, 50.0, 1000.0}) {
    driver::PointScene s;
    s.material.model = ModelKind::Enriched;
    s.material.elastic = {test::kE, test::kNu, Hypothesis::PlaneStress};
    s.material.tensileStrength = test::kFt;
    s.material.softeningModulus = solved.softeningModulus;
    s.material.softeningExponent = test::kN;
    s.material.bandWidth = test::kBandWidth;
    s.effectiveSize = bigH;
    driver::PresetPath p;
    p.name = "uniaxial_tension";
    p.strain = 5e-5;
    p.increments = 10;
    p.opening = 20.0;  // mm: the traction there is below 1e-4 f_t'
    p.firstOpeningIncrement = 1e-7;
    s.path = driver::presetSegments(p, 0.2);
    s.path.back().increments = 2000;
    const driver::PointRun run = driver::runPoint(s);
    ASSERT_TRUE(run.completed) << run.failure;
    EXPECT_NEAR(driver::summarise(s, run).energyPerArea, 0.11, 0.005 * 0.11) << "H = " << bigH;
  }
}

}  // namespace
}  // namespace ecm
