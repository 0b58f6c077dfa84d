// Scenes are checked at the edge: unknown, missing and out-of-range keys give FILE:LINE and the
// reason; the tool exits 2 on them, and 0 with its outputs on a good scene.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "../run_tool.hpp"
#include "cohesive/scene.hpp"
#include "io/yaml_input.hpp"

namespace ecm::cohesive {
namespace {

const std::string kBeam = R"(# Units: mm, N, MPa, tonne, s.
name: beam
problem: beam
thickness: 50
cell: 2.5
material: {youngs_modulus: 37000, poisson_ratio: 0.2, tensile_strength: 3.9, fracture_energy: 0.1432}
law: hordijk
beam: {depth: 50, length: 175, span: 125, notch_width: 2.5, notch_depth: 25, cmod_gauge: 20, supports: node, load: node}
control: {final: 0.05, max_step: 0.001}
)";

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

// The message of the InputError the text raises ("" if it raises none).
std::string rejection(const std::string& text) {
  try {
    parseScene(text, "scene.yaml");
  } catch (const io::InputError& e) {
    return e.what();
  }
  return "";
}

TEST(CohesiveScene, ReadsAGoodScene) {
  const Scene s = parseScene(kBeam, "scene.yaml");
  EXPECT_EQ(s.law.kind, LawKind::hordijk);
  EXPECT_EQ(s.law.hordijk.initialStiffness, 1e6);  // no band block: the stated default
  EXPECT_FALSE(s.beam.supportBox);
}

TEST(CohesiveScene, RejectsAnUnknownKeyWithFileAndLine) {
  const std::string m = rejection(replaced(kBeam, "cell: 2.5", "cell: 2.5\ncel_size: 1"));
  EXPECT_NE(m.find("scene.yaml:6:"), std::string::npos) << m;
  EXPECT_NE(m.find("cel_size"), std::string::npos) << m;
}

TEST(CohesiveScene, RejectsAMissingKeyWithFileAndLine) {
  const std::string m = rejection(replaced(kBeam, "notch_depth: 25, ", ""));
  EXPECT_NE(m.find("scene.yaml:8:"), std::string::npos) << m;
  EXPECT_NE(m.find("notch_depth"), std::string::npos) << m;
}

TEST(CohesiveScene, RejectsOutOfRangeValuesWithFileAndLine) {
  std::string m = rejection(replaced(kBeam, "poisson_ratio: 0.2", "poisson_ratio: 0.7"));
  EXPECT_NE(m.find("scene.yaml:6:"), std::string::npos) << m;
  EXPECT_NE(m.find("poisson_ratio"), std::string::npos) << m;
  // A notch deeper than the beam.
  m = rejection(replaced(kBeam, "notch_depth: 25", "notch_depth: 60"));
  EXPECT_NE(m.find("scene.yaml:8:"), std::string::npos) << m;
  // Hordijk's stiffness below the curve's steepest slope (143.8 MPa/mm here).
  m = rejection(replaced(kBeam, "law: hordijk", "law: hordijk\nhordijk: {initial_stiffness: 100}"));
  EXPECT_NE(m.find("scene.yaml:8:"), std::string::npos) << m;
  EXPECT_NE(m.find("steepest"), std::string::npos) << m;
  // A band law that does not dissipate G_F.
  m = rejection(replaced(kBeam, "law: hordijk", "law: band\nband: {band_width: 0.05, softening_modulus: 8.184, softening_exponent: 0.128}"));
  EXPECT_NE(m.find("scene.yaml:8:"), std::string::npos) << m;
  EXPECT_NE(m.find("ecm-calibrate"), std::string::npos) << m;
}

TEST(CohesiveTool, ExitsTwoOnBadInputAndWritesItsOutputsOnAGoodScene) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "ecm-cohesive-tool-test";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "bad.yaml") << replaced(kBeam, "cell: 2.5", "cell: -1");
  std::ofstream(dir / "good.yaml") << kBeam;
  const test::ToolRun bad = test::runTool(ECM_COHESIVE, test::shellQuoted(dir / "bad.yaml") + " --out " + test::shellQuoted(dir / "bad"), dir);
  EXPECT_EQ(bad.status, io::kExitBadInput);
  EXPECT_NE(bad.err.find("ecm-cohesive: error: "), std::string::npos) << bad.err;
  EXPECT_NE(bad.err.find("bad.yaml:5:"), std::string::npos) << bad.err;
  const test::ToolRun good = test::runTool(ECM_COHESIVE, test::shellQuoted(dir / "good.yaml") + " --out " + test::shellQuoted(dir / "out") + " --cell 5", dir);
  EXPECT_EQ(good.status, io::kExitDone) << good.err;
  for (const char* f : {"history.csv", "ligament.csv", "summary.json"}) EXPECT_TRUE(std::filesystem::exists(dir / "out" / f)) << f;
  const test::ToolRun law = test::runTool(ECM_COHESIVE, test::shellQuoted(dir / "good.yaml") + " --out " + test::shellQuoted(dir / "x") + " --law band", dir);
  EXPECT_EQ(law.status, io::kExitBadInput);  // no band block in the scene
}

}  // namespace
}  // namespace ecm::cohesive
