// ecm-point scene files: bad input is rejected with the file, the line and the reason.
#include "driver/point_scene_yaml.hpp"

#include <gtest/gtest.h>

namespace ecm {
namespace {

const std::string kMaterial = R"(material:
  name: concrete
  model: enriched
  hypothesis: plane_stress
  youngs_modulus: 32000
  poisson_ratio: 0.2
  tensile_strength: 3.0
  softening_modulus: 8.184
  softening_exponent: 0.128
  band_width: 0.05
)";

// Expects an io::InputError whose message names the scene, the line and contains `reason`.
void expectRejected(const std::string& body, int line, const std::string& reason) {
  try {
    readPointScene(io::parseYaml(kMaterial + body, "scene.yaml"));
    FAIL() << "accepted:\n" << body;
  } catch (const io::InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("scene.yaml:" + std::to_string(line) + ":"), std::string::npos) << what;
    EXPECT_NE(what.find(reason), std::string::npos) << what;
  }
}

TEST(PointSceneYaml, ReadsAPresetScene) {
  const PointScene s = readPointScene(io::parseYaml(kMaterial + R"(effective_size: 10
path: {preset: uniaxial_tension, strain: 2.0e-4, increments: 50, opening: 0.3}
)",
                                                    "scene.yaml"));
  EXPECT_EQ(s.effectiveSize, 10.0);
  ASSERT_EQ(s.path.size(), 2u);
  EXPECT_EQ(s.path[0].control[1], Control::Stress);
  EXPECT_TRUE(s.path[1].openingControl);
  EXPECT_EQ(s.path[1].openingTarget, 0.3);
}

TEST(PointSceneYaml, RejectsUnknownKeys) {
  expectRejected("effective_size: 10\nstrain_rate: 1\npath: {preset: uniaxial_tension, strain: 1e-4, increments: 5}\n", 12,
                 "unknown key 'strain_rate'");
}

TEST(PointSceneYaml, RejectsMissingKeys) {
  expectRejected("path: {preset: uniaxial_tension, strain: 1e-4, increments: 5}\n", 1, "effective_size");
}

TEST(PointSceneYaml, RejectsWrongTypes) {
  expectRejected("effective_size: ten\npath: {preset: uniaxial_tension, strain: 1e-4, increments: 5}\n", 11, "effective_size");
}

TEST(PointSceneYaml, RejectsZeroIncrements) {
  expectRejected("effective_size: 10\npath: {preset: uniaxial_tension, strain: 1e-4, increments: 0}\n", 12, "increments");
}

TEST(PointSceneYaml, RejectsAnEffectiveSizeBelowTheSmallestOneAndGivesTheBound) {
  // The bound is h (1 + 1e-6) = 0.05000005 mm for h = 0.05 mm (docs/model.md).
  expectRejected("effective_size: 0.05\npath: {preset: uniaxial_tension, strain: 1e-4, increments: 5}\n", 11,
                 "0.05000005 mm");
  expectRejected("effective_size: 0.05000000005\npath: {preset: uniaxial_tension, strain: 1e-4, increments: 5}\n", 11,
                 "below the smallest effective size");
  EXPECT_NO_THROW(readPointScene(io::parseYaml(kMaterial + "effective_size: 0.05000005\n"
                                               "path: {preset: uniaxial_tension, strain: 1e-4, increments: 5}\n", "s.yaml")));
}

TEST(PointSceneYaml, RejectsAComponentGivenTwiceOrNotAtAll) {
  expectRejected("effective_size: 10\npath:\n  segments:\n    - {eps_xx: 1e-4, sig_xx: 0, sig_yy: 0, sig_xy: 0, increments: 5}\n",
                 14, "exactly one of 'eps_xx'");
  expectRejected("effective_size: 10\npath:\n  segments:\n    - {sig_yy: 0, sig_xy: 0, increments: 5}\n", 14,
                 "exactly one of 'eps_xx'");
}

TEST(PointSceneYaml, RejectsOpeningControlWithoutABand) {
  const std::string smeared = R"(material:
  model: smeared_crack
  hypothesis: plane_stress
  youngs_modulus: 32000
  poisson_ratio: 0.2
  tensile_strength: 3.0
  softening_modulus: 8.184
  softening_exponent: 0.128
effective_size: 10
path: {preset: uniaxial_tension, strain: 1e-4, increments: 5, opening: 0.2}
)";
  try {
    readPointScene(io::parseYaml(smeared, "scene.yaml"));
    FAIL();
  } catch (const io::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("scene.yaml:10:"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("opening control needs a band"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace ecm
