// The table law's input: the scene's `table` block and its CSV file. A bad row is named by the
// CSV's FILE:LINE, a missing file or a too low K0 by the scene's; the tool exits 2 on them and 1
// (naming the opening) when a run opens the interface past the table's last row.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "../run_tool.hpp"
#include "cohesive/scene.hpp"
#include "io/yaml_input.hpp"

namespace ecm::cohesive {
namespace {

// A bar of the DEN concrete (f_t' 3 MPa, E/h = 640000 MPa/mm) with a table law; line 8 holds the
// table block.
const std::string kScene = R"(# Units: mm, N, MPa, tonne, s.
name: bar
problem: bar
thickness: 10
cell: 10
material: {youngs_modulus: 32000, poisson_ratio: 0.2, tensile_strength: 3.0, fracture_energy: 0.11}
law: table
table: {file: law.csv, initial_stiffness: 640000}
bar: {length: 50, height: 10}
control: {final: 0.05, max_step: 0.001}
)";

// Rows on lines 3-7.
const std::string kTable = R"(# a softening curve
opening_mm,traction_MPa
0,3.0
0.001,2.6
0.01,1.2
0.05,0.2
0.2,0
)";

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

struct Folder {
  std::filesystem::path path;
  explicit Folder(const std::string& name) : path(std::filesystem::temp_directory_path() / name) {
    std::filesystem::remove_all(path);
    std::filesystem::create_directories(path);
  }
  ~Folder() { std::filesystem::remove_all(path); }
  void write(const std::string& file, const std::string& text) const { std::ofstream(path / file) << text; }
};

// The message of the InputError that reading scene.yaml (beside law.csv) raises, "" if none.
std::string rejection(const Folder& f, const std::string& scene, const std::string& table) {
  f.write("scene.yaml", scene);
  f.write("law.csv", table);
  try {
    readScene(f.path / "scene.yaml");
  } catch (const io::InputError& e) {
    return e.what();
  }
  return "";
}

TEST(CohesiveTableInput, ReadsTheTableBesideTheScene) {
  const Folder f("ecm-cohesive-table-good");
  EXPECT_EQ(rejection(f, kScene, kTable), "");
  const Scene s = readScene(f.path / "scene.yaml");
  EXPECT_EQ(s.law.kind, LawKind::table);
  EXPECT_EQ(s.law.table.opening.size(), 5u);
  EXPECT_EQ(s.law.table.traction[4], 0.0);
  EXPECT_EQ(s.law.table.initialStiffness, 640000.0);
  EXPECT_EQ(s.law.table.source, (f.path / "law.csv").string());
}

TEST(CohesiveTableInput, RejectsBadRowsWithTheTablesFileAndLine) {
  const Folder f("ecm-cohesive-table-rows");
  std::string m = rejection(f, kScene, replaced(kTable, "0.05,0.2", "0.005,0.2"));  // unsorted
  EXPECT_NE(m.find("law.csv:6:"), std::string::npos) << m;
  EXPECT_NE(m.find("increase"), std::string::npos) << m;
  m = rejection(f, kScene, replaced(kTable, "0.01,1.2", "0.01,-1.2"));  // a negative traction
  EXPECT_NE(m.find("law.csv:5:"), std::string::npos) << m;
  EXPECT_NE(m.find("-1.2 MPa"), std::string::npos) << m;
  m = rejection(f, kScene, replaced(kTable, "0,3.0", "0.0001,3.0"));  // not from 0
  EXPECT_NE(m.find("law.csv:3:"), std::string::npos) << m;
  m = rejection(f, kScene, replaced(kTable, "0.01,1.2", "0.01,1.2,7"));  // a third column
  EXPECT_NE(m.find("law.csv:5:"), std::string::npos) << m;
  m = rejection(f, kScene, replaced(kTable, "opening_mm,traction_MPa", "opening_m,traction_Pa"));  // other units
  EXPECT_NE(m.find("law.csv:2:"), std::string::npos) << m;
  EXPECT_NE(m.find("opening_mm,traction_MPa"), std::string::npos) << m;
}

TEST(CohesiveTableInput, RejectsAMissingFileALowStiffnessAndAStrayBlockAtTheScenesLine) {
  const Folder f("ecm-cohesive-table-scene");
  std::string m = rejection(f, replaced(kScene, "file: law.csv", "file: missing.csv"), kTable);
  EXPECT_NE(m.find("scene.yaml:8:"), std::string::npos) << m;
  EXPECT_NE(m.find((f.path / "missing.csv").string()), std::string::npos) << m;
  // 2.6 MPa at 0.001 mm needs K0 > 2600 MPa/mm.
  m = rejection(f, replaced(kScene, "initial_stiffness: 640000", "initial_stiffness: 2000"), kTable);
  EXPECT_NE(m.find("scene.yaml:8:"), std::string::npos) << m;
  EXPECT_NE(m.find("too low"), std::string::npos) << m;
  // A table of another concrete: its first row is not the scene's f_t'.
  m = rejection(f, kScene, replaced(kTable, "0,3.0", "0,3.9"));
  EXPECT_NE(m.find("scene.yaml:8:"), std::string::npos) << m;
  EXPECT_NE(m.find("tensile_strength"), std::string::npos) << m;
  m = rejection(f, replaced(kScene, "table: {file: law.csv, initial_stiffness: 640000}", ""), kTable);
  EXPECT_NE(m.find("needs the block table"), std::string::npos) << m;
  m = rejection(f, replaced(kScene, "law: table", "law: hordijk"), kTable);  // the table block with another law
  EXPECT_NE(m.find("scene.yaml:8:"), std::string::npos) << m;
  EXPECT_NE(m.find("only with law: table"), std::string::npos) << m;
}

TEST(CohesiveTableInput, TheToolExitsTwoOnABadTableAndOneNamingTheOpeningPastItsEnd) {
  const Folder f("ecm-cohesive-table-tool");
  f.write("scene.yaml", kScene);
  f.write("law.csv", replaced(kTable, "0.05,0.2", "0.005,0.2"));
  const test::ToolRun bad = test::runTool(ECM_COHESIVE, test::shellQuoted(f.path / "scene.yaml") + " --out " + test::shellQuoted(f.path / "bad"), f.path);
  EXPECT_EQ(bad.status, io::kExitBadInput);
  EXPECT_NE(bad.err.find("law.csv:6:"), std::string::npos) << bad.err;
  // The table ends at 0.02 mm; the bar is pulled to 0.05 mm.
  f.write("law.csv", "opening_mm,traction_MPa\n0,3.0\n0.001,2.6\n0.01,1.2\n0.02,0.6\n");
  const test::ToolRun past = test::runTool(ECM_COHESIVE, test::shellQuoted(f.path / "scene.yaml") + " --out " + test::shellQuoted(f.path / "out"), f.path);
  EXPECT_EQ(past.status, io::kExitRunFailed) << past.err;
  EXPECT_NE(past.err.find("mm is past the end of the traction-opening table"), std::string::npos) << past.err;
  EXPECT_NE(past.err.find("(its last row is at 0.02 mm)"), std::string::npos) << past.err;
  EXPECT_NE(past.out.find("rows to opening 0.02 mm, area"), std::string::npos) << past.out;
  EXPECT_TRUE(std::filesystem::exists(f.path / "out" / "summary.json"));
  // --law table on a scene without a table block is bad input.
  f.write("band.yaml", replaced(replaced(kScene, "law: table", "law: band"), "table: {file: law.csv, initial_stiffness: 640000}",
                                "band: {band_width: 0.05, softening_modulus: 8.184, softening_exponent: 0.128}"));
  const test::ToolRun noTable = test::runTool(ECM_COHESIVE, test::shellQuoted(f.path / "band.yaml") + " --out " + test::shellQuoted(f.path / "x") + " --law table", f.path);
  EXPECT_EQ(noTable.status, io::kExitBadInput);
  EXPECT_NE(noTable.err.find("needs the block table"), std::string::npos) << noTable.err;
}

}  // namespace
}  // namespace ecm::cohesive
