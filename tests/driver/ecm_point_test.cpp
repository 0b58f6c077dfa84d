// End to end: the ecm-point tool's exit status (io/cli_exit.hpp): 0 done, 1 the run stopped
// early (outputs kept), 2 bad input (a bad value here; a missing file and a bad command line: tests/cli).
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "io/temp_dir.hpp"
#include "run_tool.hpp"

namespace ecm::driver::test {
namespace {

namespace fs = std::filesystem;
using namespace ecm::test;  // expectContains, runTool, shellQuoted, TempDir, ToolRun

ToolRun point(const std::string& args, const TempDir& tmp) { return runTool(ECM_POINT, args, tmp.path()); }

// The paper's concrete (data/materials/den-concrete.yaml) in uniaxial tension.
std::string tensionScene(double size, const std::string& extra = "") {
  return "name: tension\nmaterial: {file: den-concrete.yaml}\neffective_size: " + std::to_string(size) + "\n" + extra +
         "path: {preset: uniaxial_tension, strain: 1.0e-3, increments: 100}\n";
}

TEST(EcmPoint, ABadSceneValueIsBadInputWithTheLine) {
  TempDir tmp;
  const fs::path scene = tmp.write("bad.yaml", tensionScene(10.0, "colour: red\n"));
  const ToolRun r = point(shellQuoted(scene) + " --out " + shellQuoted(tmp.path() / "out"), tmp);
  EXPECT_EQ(r.status, ecm::io::kExitBadInput);
  expectContains(r.err, "bad.yaml:4: unknown key 'colour'");
}

TEST(EcmPoint, ACompletedRunIsDone) {
  TempDir tmp;
  const fs::path scene = tmp.write("tension.yaml", tensionScene(10.0));
  const ToolRun r = point(shellQuoted(scene) + " --out " + shellQuoted(tmp.path() / "out"), tmp);
  EXPECT_EQ(r.status, ecm::io::kExitDone) << r.err;
  EXPECT_TRUE(fs::exists(tmp.path() / "out" / "summary.json"));
}

// H = 500 mm is beyond the snap-back size (195.55 mm): with snap_back: stop the run stops at the
// limit point, and what it recorded up to there is written.
TEST(EcmPoint, ARunThatStopsEarlyExitsOneWithItsOutputs) {
  TempDir tmp;
  const fs::path scene = tmp.write("stops.yaml", tensionScene(500.0, "snap_back: stop\n"));
  const ToolRun r = point(shellQuoted(scene) + " --out " + shellQuoted(tmp.path() / "out"), tmp);
  EXPECT_EQ(r.status, ecm::io::kExitRunFailed) << r.err;
  expectContains(r.err, "run stopped: snap-back");
  EXPECT_TRUE(fs::exists(tmp.path() / "out" / "history.csv"));
}

}  // namespace
}  // namespace ecm::driver::test
