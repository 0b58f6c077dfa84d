// End to end: the ecm-study tool's exit status (io/cli_exit.hpp): 0 every run completed, 1 some
// run failed, 2 bad input (a missing file, a bad key or value, a bad command line).
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "../io/temp_dir.hpp"
#include "../run_tool.hpp"

namespace ecm::study::test {
namespace {

namespace fs = std::filesystem;
using namespace ecm::test;  // expectContains, runTool, shellQuoted, TempDir, ToolRun

ToolRun study(const std::string& args, const TempDir& tmp) { return runTool(ECM_STUDY, args, tmp.path()); }

// Two increment counts of the enriched point in uniaxial tension (a few milliseconds).
std::string pointStudy(const std::string& extra = "") {
  return "name: point-exit\n"
         "kind: point\n"
         "scene: " + std::string(ECM_SOURCE_DIR) + "/data/point/uniaxial-tension-H10.yaml\n"
         "knobs:\n"
         "  path.increments: [20, 200]\n"
         "reference: {closed_form: uniaxial_tension}\n" + extra;
}

TEST(EcmStudy, AnUnknownKeyIsBadInputWithTheLine) {
  TempDir tmp;
  const fs::path file = tmp.write("study.yaml", pointStudy("repeats: 2\n"));
  const ToolRun r = study(shellQuoted(file) + " --list", tmp);
  EXPECT_EQ(r.status, ecm::io::kExitBadInput);
  expectContains(r.err, "study.yaml:7: unknown key 'repeats'");
}

TEST(EcmStudy, ACompletedStudyAndItsListAreDone) {
  TempDir tmp;
  const fs::path file = tmp.write("study.yaml", pointStudy());
  const ToolRun list = study(shellQuoted(file) + " --list", tmp);
  EXPECT_EQ(list.status, ecm::io::kExitDone) << list.err;
  expectContains(list.out, "2 runs");
  const ToolRun r = study(shellQuoted(file) + " -q --out " + shellQuoted(tmp.path() / "out"), tmp);
  EXPECT_EQ(r.status, ecm::io::kExitDone) << r.err;
  EXPECT_TRUE(fs::exists(tmp.path() / "out" / "study.csv"));
}

// H = 500 mm is beyond the snap-back size (195.55 mm): with snap_back: stop every run stops at
// the limit point. The study itself completes: its table is written, the status says the runs failed.
TEST(EcmStudy, FailedRunsExitOneWithTheTable) {
  TempDir tmp;
  const fs::path file = tmp.write("study.yaml",
                                  "name: point-stops\n"
                                  "kind: point\n"
                                  "scene: " + std::string(ECM_SOURCE_DIR) + "/data/point/uniaxial-tension-H10.yaml\n"
                                  "set: {effective_size: 500.0, snap_back: stop}\n"
                                  "knobs:\n"
                                  "  path.increments: [20, 200]\n"
                                  "reference: {run: {path.increments: 200}}\n");
  const ToolRun r = study(shellQuoted(file) + " -q --out " + shellQuoted(tmp.path() / "out"), tmp);
  EXPECT_EQ(r.status, ecm::io::kExitRunFailed) << r.err;
  expectContains(r.out, "failed");
  // The closing lines name every run that did not complete, after the count.
  expectContains(r.err, "2 of 2 runs did not complete:\n  run 1: failed (");
  expectContains(r.err, "  run 2 (reference): failed (");
  EXPECT_TRUE(fs::exists(tmp.path() / "out" / "study.csv"));
}

}  // namespace
}  // namespace ecm::study::test
