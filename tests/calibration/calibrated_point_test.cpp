// One material, two independent computations: the calibration's quadrature fixes E_p for
// G_F; the point driver, running the enriched model on that material to complete failure,
// must dissipate the same G_F (within 0.5%).
#include <gtest/gtest.h>

#include "calibration/fracture_energy.hpp"
#include "driver/point_driver.hpp"

namespace ecm {
namespace {

TEST(CalibratedMaterial, PointDriverDissipatesTheCalibratedFractureEnergy) {
  // The paper's concrete: E = 32000, nu = 0.2, f_t' = 3.0 MPa, G_F = 0.11 N/mm, h = 0.05 mm, n = 0.128.
  const DamageLawParams shape{32000.0, 3.0, 1.0, 0.128};
  const auto solved = calibration::solveSofteningModulus(shape, 0.11, 0.05);
  for (double bigH : {2.5, 50.0, 1000.0}) {
    driver::PointScene s;
    s.material.model = ModelKind::Enriched;
    s.material.elastic = {32000.0, 0.2, Hypothesis::PlaneStress};
    s.material.tensileStrength = 3.0;
    s.material.softeningModulus = solved.softeningModulus;
    s.material.softeningExponent = 0.128;
    s.material.bandWidth = 0.05;
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
