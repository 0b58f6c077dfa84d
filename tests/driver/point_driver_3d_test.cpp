// ecm-point in 3D (driver/point_driver_3d.hpp): the uniaxial-stress preset against its closed
// form (docs/model.md, "The point in 3D" (b)), the rotated-axis and triaxial presets, and bad
// scene input rejected with file, line and reason.
#include "driver/point_driver_3d.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "material/damage_function.hpp"
#include "paper_constants.hpp"

namespace ecm::driver {
namespace {

const std::string kScene = R"(material:
  name: concrete
  model: enriched
  hypothesis: plane_stress
  youngs_modulus: 32000
  poisson_ratio: 0.2
  tensile_strength: 3.0
  softening_modulus: 8.184
  softening_exponent: 0.128
  band_width: 0.05
hypothesis: three_dimensional
effective_size: 10
)";

TEST(PointDriver3D, ARowThatIsNotANumberEndsTheRunAndNamesItsIncrement) {
  // An elastic point strained to 1e305 in one increment: E eps overflows a double, the stress is
  // infinite and the work NaN. The run stops at increment 1, says why, and keeps row 0.
  const PointScene3 s = readPointScene3(io::parseYaml(
      "material: {name: glass, model: linear_elastic, hypothesis: plane_stress, youngs_modulus: 32000, poisson_ratio: 0.2}\n"
      "hypothesis: three_dimensional\neffective_size: 10\n"
      "path:\n  segments:\n    - {eps_xx: 1.0e305, eps_yy: 0, eps_zz: 0, gamma_yz: 0, gamma_xz: 0, gamma_xy: 0, increments: 1}\n", "s.yaml"));
  const PointRun3 run = runPoint3D(s);
  EXPECT_FALSE(run.completed);
  EXPECT_NE(run.failure.find("increment 1 (segment 1)"), std::string::npos) << run.failure;
  EXPECT_NE(run.failure.find("not a number"), std::string::npos) << run.failure;
  EXPECT_EQ(run.history.size(), 1u);
}

TEST(PointDriver3D, UniaxialTensionFollowsTheFrozenLateralBandClosedForm) {
  // sigma_xx at the band's integrity x: x ((lambda + 2 mu) e + 2 lambda eps0) with e from
  // (lambda + 2 mu) e^2 + 4 lambda eps0 e + 4 (lambda + mu) eps0^2 = 2 F(x), eps0 = -nu f_t'/E
  // (Eqs. (11)-(12), both lateral band strains frozen at onset); the other stresses at zero.
  const PointScene3 s = readPointScene3(io::parseYaml(kScene + "path: {preset: uniaxial_tension, strain: 4.0e-4, increments: 200}\n", "s.yaml"));
  const PointRun3 run = runPoint3D(s);
  ASSERT_TRUE(run.completed) << run.failure;
  const double e = test::kE, nu = test::kNu, mu = e / (2 * (1 + nu)), lambda = e * nu / ((1 + nu) * (1 - 2 * nu));
  const double eps0 = -nu * test::kFt / e, a11 = lambda + 2 * mu;
  const DamageLawParams law{test::kE, test::kFt, test::kEp, test::kN};
  int onsetRows = 0, checked = 0;
  for (const HistoryRow3& r : run.history) {
    onsetRows += r.onset;
    EXPECT_LE(r.stress.tail<5>().cwiseAbs().maxCoeff(), 1e-8 * test::kFt);
    if (r.damage == 0.0) continue;
    const double c = 4 * (lambda + mu) * eps0 * eps0 - 2 * damageFunction(law, r.integrity);
    const double normal = (-2 * lambda * eps0 + std::sqrt(4 * lambda * lambda * eps0 * eps0 - a11 * c)) / a11;
    EXPECT_NEAR(r.stress[0], r.integrity * (a11 * normal + 2 * lambda * eps0), 1e-7 * test::kFt);
    ++checked;
  }
  EXPECT_EQ(onsetRows, 1);
  EXPECT_GT(checked, 100);
}

// Whatever the number of increments, the stress maximum gets a row of its own (docs/inputs.md):
// the largest row is the closed form's maximum of sigma_xx(x) (the test above's), not the largest
// of the increments' ends. With 6 increments to 4e-4 the ends straddle the peak.
TEST(PointDriver3D, TheStressMaximumGetsARowOfItsOwn) {
  const double e = test::kE, nu = test::kNu, mu = e / (2 * (1 + nu)), lambda = e * nu / ((1 + nu) * (1 - 2 * nu));
  const double eps0 = -nu * test::kFt / e, a11 = lambda + 2 * mu;
  const DamageLawParams law{test::kE, test::kFt, test::kEp, test::kN};
  const auto sigma = [&](double x) {
    const double c = 4 * (lambda + mu) * eps0 * eps0 - 2 * damageFunction(law, x);
    const double normal = (-2 * lambda * eps0 + std::sqrt(4 * lambda * lambda * eps0 * eps0 - a11 * c)) / a11;
    return x * (a11 * normal + 2 * lambda * eps0);
  };
  double closedForm = 0.0;
  for (double x = 1e-4; x <= 1.0; x += 1e-6) closedForm = std::max(closedForm, sigma(x));
  for (const int increments : {6, 13, 200}) {
    const PointScene3 s = readPointScene3(io::parseYaml(
        kScene + "path: {preset: uniaxial_tension, strain: 4.0e-4, increments: " + std::to_string(increments) + "}\n", "s.yaml"));
    const PointRun3 run = runPoint3D(s);
    ASSERT_TRUE(run.completed) << run.failure;
    double peak = 0.0;
    for (const HistoryRow3& r : run.history) peak = std::max(peak, r.stress[0]);
    EXPECT_NEAR(peak, closedForm, 1e-6 * test::kFt) << increments << " increments";
  }
}

TEST(PointDriver3D, RotatedAxisAndTriaxialPresetsRun) {
  const PointScene3 r = readPointScene3(
      io::parseYaml(kScene + "path: {preset: rotated_axis, direction: [1, 2, 2], strain: 1.0e-3, increments: 100}\n", "r.yaml"));
  const PointRun3 a = runPoint3D(r);
  ASSERT_TRUE(a.completed) << a.failure;
  EXPECT_NEAR(a.history.back().crackNormal.dot(Vec3(1, 2, 2) / 3.0), 1.0, 1e-12);
  const PointScene3 t = readPointScene3(
      io::parseYaml(kScene + "path: {preset: triaxial, confinement: -1.0, strain: 1.0e-3, increments: 100}\n", "t.yaml"));
  const PointRun3 b = runPoint3D(t);
  ASSERT_TRUE(b.completed) << b.failure;
  EXPECT_NEAR(b.history.back().stress[1], -1.0, 1e-8 * test::kFt);
  EXPECT_NEAR(b.history.back().crackNormal[0], 1.0, 1e-12);
  EXPECT_GT(b.history.back().damage, 0.5);
}

TEST(PointDriver3D, BadScenesAreRejectedWithLineAndReason) {
  const auto rejected = [](const std::string& body, const std::string& reason) {
    try {
      readPointScene3(io::parseYaml(kScene + body, "bad.yaml"));
      ADD_FAILURE() << "accepted: " << body;
    } catch (const io::InputError& e) {
      EXPECT_NE(std::string(e.what()).find("bad.yaml:"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(reason), std::string::npos) << e.what();
    }
  };
  rejected("path: {segments: [{increments: 10, eps_xx: 1.0e-4, sig_yy: 0, sig_zz: 0, sig_yz: 0, sig_xz: 0}]}\n", "gamma_xy");
  rejected("path: {preset: rotated_axis, strain: 1.0e-3, increments: 10}\n", "direction");
  rejected("path: {preset: uniaxial_tension, strain: 1.0e-3, increments: 10, ratio: 2}\n", "ratio");
}

}  // namespace
}  // namespace ecm::driver
