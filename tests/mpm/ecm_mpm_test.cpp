// End to end: the exit status of ecm-mpm and ecm-rve (io/cli_exit.hpp): 0 completed, 1 the run
// failed (outputs kept), 2 bad input (a missing file, a bad value, a bad command line, an output
// folder that cannot be used), 3 stopped with a checkpoint (ecm-mpm: a signal or --max-steps).
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <tuple>

#include "../io/temp_dir.hpp"
#include "../run_tool.hpp"
#include "io/cli_exit.hpp"
#include "mpm/core/errors.hpp"

namespace ecm::mpm::test {
namespace {

namespace fs = std::filesystem;
using namespace ecm::test;  // expectContains, readFile, runTool, shellQuoted, TempDir, ToolRun

const fs::path kBlock = fs::path(ECM_SOURCE_DIR) / "data" / "mpm" / "tension-block.yaml";

ToolRun mpm(const std::string& args, const TempDir& tmp) { return runTool(ECM_MPM, args, tmp.path()); }

// A free elastic square thrown at 1e6 mm/s across a 10 mm grid: it leaves the grid within the
// first 1e-5 s of its 1e-4 s.
const char* kThrownSquare =
    "name: thrown\n"
    "grid: {origin: [0, 0], cell_size: [1, 1], cells: [10, 6]}\n"
    "thickness: 1\n"
    "particles_per_cell: 2\n"
    "materials:\n"
    "  - {name: elastic, model: linear_elastic, hypothesis: plane_stress, youngs_modulus: 32000,\n"
    "     poisson_ratio: 0.2, density: 2.4e-9}\n"
    "bodies:\n"
    "  - {rectangle: {min: [2, 2], max: [4, 4]}, material: elastic, initial_velocity: [1.0e6, 0]}\n"
    "end_time: 1.0e-4\n"
    "output_interval: 1.0e-6\n";

// (A missing scene, an unknown option, --help and an output folder that is a file: tests/cli.)
TEST(EcmMpm, ThreadsOutOfRangeAndAnUnknownPresetAreBadInput) {
  TempDir tmp;
  const ToolRun threads = mpm(shellQuoted(kBlock) + " --threads=-1", tmp);
  EXPECT_EQ(threads.status, ecm::io::kExitBadInput);
  expectContains(threads.err, "threads");
  EXPECT_EQ(mpm(shellQuoted(kBlock) + " --preset no-such-preset", tmp).status, ecm::io::kExitBadInput);
}

TEST(EcmMpm, ABadSceneValueIsBadInputWithTheLine) {
  TempDir tmp;
  const fs::path scene = tmp.write("bad.yaml", std::string(kThrownSquare) + "colour: red\n");
  const ToolRun r = mpm(shellQuoted(scene) + " -q --out " + shellQuoted(tmp.path() / "out"), tmp);
  EXPECT_EQ(r.status, ecm::io::kExitBadInput);
  expectContains(r.err, "bad.yaml:12: unknown key 'colour'");
}

// The status names the failure's kind (io/cli_exit.hpp, mpm/core/errors.cpp): 10, left_grid.
TEST(EcmMpm, AFailedRunExitsWithItsKindsStatusAndKeepsItsOutputs) {
  TempDir tmp;
  const fs::path scene = tmp.write("thrown.yaml", kThrownSquare);
  const fs::path out = tmp.path() / "out";
  const ToolRun r = mpm(shellQuoted(scene) + " -q --no-vtu --no-plot --out " + shellQuoted(out), tmp);
  EXPECT_EQ(r.status, 10) << r.err;
  EXPECT_EQ(r.status, ecm::mpm::exitStatusOf(ecm::mpm::FailureKind::LeftGrid));
  expectContains(r.err, "ecm-mpm: error: ");  // the message, for people
  const auto j = nlohmann::json::parse(readFile(out / "summary.json"));
  EXPECT_EQ(j["status"], "failed");
  EXPECT_EQ(j["failure"]["kind"], "left_grid");
  EXPECT_EQ(j["failure"]["exit_status"], r.status);
  EXPECT_TRUE(fs::exists(out / "history.csv"));
}

// Tracked crack paths were measured with linear shape functions only (docs/model.md, "Crack
// paths", Limits): a tracked scene of the enriched model with another says so on stderr; a
// linear one, a free one, or one without an enriched material says nothing of it.
TEST(EcmMpm, TrackedPathsWithAnUnmeasuredShapeFunctionAreNoted) {
  TempDir tmp;
  const std::string material = (fs::path(ECM_SOURCE_DIR) / "data" / "materials" / "den-concrete-hordijk.yaml").string();
  std::string still = kThrownSquare;
  still.replace(still.find("initial_velocity: [1.0e6, 0]"), 28, "initial_velocity: [0, 0]    ");
  still.replace(still.find("end_time: 1.0e-4"), 16, "end_time: 1.0e-6");
  std::string concrete = still;
  concrete.replace(concrete.find("  - {name: elastic,"), std::string::npos, "");
  concrete += "  - {file: " + shellQuoted(material) + "}\n"
              "bodies:\n"
              "  - {rectangle: {min: [2, 2], max: [4, 4]}, material: den-concrete-hordijk}\n"
              "end_time: 1.0e-6\n"
              "output_interval: 1.0e-6\n";
  const auto run = [&](const std::string& name, const std::string& scene, const std::string& solver) {
    const fs::path file = tmp.write(name + ".yaml", scene + solver);
    const ToolRun r = mpm(shellQuoted(file) + " -q --no-vtu --no-plot --out " + shellQuoted(tmp.path() / name), tmp);
    EXPECT_EQ(r.status, ecm::io::kExitDone) << name << ": " << r.err;
    return r.err;
  };
  expectContains(run("ugimp", concrete, "solver: {shape_function: ugimp}\n"),
                 "note: crack_path: tracked with shape_function: ugimp is not measured");
  for (const auto& [name, scene, solver] :
       {std::tuple{"linear", concrete, "solver: {shape_function: linear}\n"},
        std::tuple{"free", concrete, "solver: {shape_function: ugimp, crack_path: free}\n"},
        std::tuple{"elastic", still, "solver: {shape_function: ugimp}\n"}})
    EXPECT_EQ(run(name, scene, solver).find("note:"), std::string::npos) << name;
}

TEST(EcmMpm, MaxStepsStopsWithACheckpointThatResumesToCompletion) {
  TempDir tmp;
  const fs::path out = tmp.path() / "out";
  const std::string args = shellQuoted(kBlock) + " -q --no-vtu --no-plot -t 1";
  const ToolRun stopped = mpm(args + " --max-steps 20 --out " + shellQuoted(out), tmp);
  EXPECT_EQ(stopped.status, ecm::io::kExitStopped) << stopped.err;
  expectContains(stopped.err, "resume with:");
  EXPECT_TRUE(fs::exists(out / "checkpoint.bin"));
  const ToolRun resumed = mpm(args + " --restart " + shellQuoted(out), tmp);
  EXPECT_EQ(resumed.status, ecm::io::kExitDone) << resumed.err;
  EXPECT_FALSE(fs::exists(out / "checkpoint.bin"));  // a completed run removes it
}

TEST(EcmRve, ABadValueIsBadInputWithTheLine) {
  TempDir tmp;
  const fs::path params = tmp.write("params.yaml",
                                    "rve:\n"
                                    "  side: 10\n"
                                    "  seed: -1\n");
  const ToolRun r = runTool(ECM_RVE, shellQuoted(params) + " --out " + shellQuoted(tmp.path() / "out"), tmp.path());
  EXPECT_EQ(r.status, ecm::io::kExitBadInput) << r.err;
  expectContains(r.err, "params.yaml:3");
}

}  // namespace
}  // namespace ecm::mpm::test
