// ecm-point scene files: bad input is rejected with the file, the line and the reason.
#include "driver/point_driver_3d.hpp"
#include "driver/point_scene_yaml.hpp"

#include <gtest/gtest.h>

namespace ecm::driver {
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

TEST(PointSceneYaml, SnapBackKeyIsSharedWithMpmScenesAndTheOldKeyNamesTheNewOne) {
  const std::string path = "path: {preset: uniaxial_tension, strain: 1e-4, increments: 5}\n";
  EXPECT_EQ(readPointScene(io::parseYaml(kMaterial + "effective_size: 10\nsnap_back: stop\n" + path, "s.yaml")).snapBack,
            SnapBackPolicy::Stop);
  EXPECT_EQ(readPointScene(io::parseYaml(kMaterial + "effective_size: 10\n" + path, "s.yaml")).snapBack,
            kDefaultSnapBack);  // release (material/snap_back_policy.hpp)
  EXPECT_EQ(PointScene{}.snapBack, kDefaultSnapBack);
  EXPECT_EQ(PointScene3{}.snapBack, kDefaultSnapBack);
  expectRejected("effective_size: 10\non_snapback: jump\n" + path, 12, "snap_back: release (was jump)");
  expectRejected("effective_size: 10\nsnap_back: jump\n" + path, 12, "release");
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
}  // namespace ecm::driver

namespace ecm::driver {
namespace {

// The second-band option (docs/model.md, "A second band") in a point scene's material.
void expectSecondBandRejected(const std::string& model, const std::string& value, const std::string& rest, int line,
                              const std::string& reason) {
  std::string material = kMaterial;
  material.replace(material.find("model: enriched"), 15, "model: " + model);
  if (model != "enriched") material.replace(material.find("  band_width: 0.05\n"), 18, "");
  const std::string scene = material + "  second_band: " + value + "\n" + rest;
  try {
    readPointScene(io::parseYaml(scene, "scene.yaml"));
    FAIL() << "accepted:\n" << scene;
  } catch (const io::InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("scene.yaml:" + std::to_string(line) + ":"), std::string::npos) << what;
    EXPECT_NE(what.find(reason), std::string::npos) << what;
  }
}

const std::string kPath = "path: {preset: uniaxial_tension, strain: 2.0e-4, increments: 50}\n";

TEST(PointSceneYaml, ReadsTheSecondBandOption) {
  const PointScene s =
      readPointScene(io::parseYaml(kMaterial + "  second_band: orthogonal\neffective_size: 10\n" + kPath, "scene.yaml"));
  EXPECT_EQ(s.material.secondBand, SecondBandOption::Orthogonal);
  const PointScene off = readPointScene(io::parseYaml(kMaterial + "effective_size: 10\n" + kPath, "scene.yaml"));
  EXPECT_EQ(off.material.secondBand, SecondBandOption::Off);
}

TEST(PointSceneYaml, RejectsTheSecondBandOnAModelWithoutABand) {
  expectSecondBandRejected("smeared_crack", "orthogonal", "effective_size: 10\n" + kPath, 11, "enriched only");
  const std::string elastic =
      "material: {model: linear_elastic, hypothesis: plane_stress, youngs_modulus: 1, poisson_ratio: 0,\n"
      "  second_band: orthogonal}\neffective_size: 10\n" + kPath;
  try {
    readPointScene(io::parseYaml(elastic, "scene.yaml"));
    FAIL() << "accepted:\n" << elastic;
  } catch (const io::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("scene.yaml:2: key 'material.second_band': is used by model enriched only"),
              std::string::npos) << e.what();
  }
}

TEST(PointSceneYaml, RejectsAnUnknownSecondBandValue) {
  expectSecondBandRejected("enriched", "diagonal", "effective_size: 10\n" + kPath, 11, "orthogonal");
}

TEST(PointSceneYaml, RejectsAnEffectiveSizeWithoutRoomForTwoBands) {
  // 2 h (1 + 1e-6) = 0.1000001 mm for h = 0.05 mm.
  expectSecondBandRejected("enriched", "orthogonal", "effective_size: 0.1\n" + kPath, 12, "room for two bands");
}

TEST(PointSceneYaml, RejectsOpeningControlWithTheSecondBand) {
  expectSecondBandRejected("enriched", "orthogonal",
                           "effective_size: 10\npath: {preset: uniaxial_tension, strain: 2.0e-4, increments: 50, opening: 0.3}\n",
                           13, "opening control drives the opening of one band");
}

}  // namespace
}  // namespace ecm::driver
