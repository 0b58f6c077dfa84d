// Checkpoints of scenes with platens (mpm/scene/platen.hpp): a run stopped and resumed, or killed
// with SIGKILL and restarted, writes the uninterrupted run's history.csv, particles and crack
// paths byte for byte, and its summary's platen forces; explicit and implicit. The checkpoint
// holds each platen's displacement, velocity and force and the run's largest platen forces.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>

#include "../io/temp_dir.hpp"
#include "mpm/run.hpp"
#include "mpm/scene/scene_yaml.hpp"
#include "test_scenes.hpp"
#include "run_helpers.hpp"

namespace ecm::mpm::test {
namespace {

using namespace ecm::test;  // readFile, TempDir
namespace fs = std::filesystem;

RunOptions quiet(const fs::path& dir, int threads = 1) {
  RunOptions o = quietRun(dir);
  o.threads = threads;
  o.sceneHash = 7;
  return o;
}

nlohmann::json platensOf(const fs::path& dir) { return nlohmann::json::parse(readFile(dir / "summary.json"))["platens"]; }

// history.csv, particles_final.csv and (tracked runs) crack_paths.csv of two runs, byte for byte,
// and the platens of their summaries.
void expectSameRun(const fs::path& a, const fs::path& b) {
  for (const char* name : {"history.csv", "particles_final.csv", "crack_paths.csv"}) {
    if (!fs::exists(a / name)) continue;
    EXPECT_TRUE(readFile(a / name) == readFile(b / name)) << name << " differs";
  }
  EXPECT_EQ(platensOf(a), platensOf(b));
}

// The notched cracking block (test_scenes.hpp) pulled at its top edge by a platen instead of a
// prescribed velocity: y driven by a displacement history, x and the rotation free, so that the
// platen moves and carries a force on each degree of freedom while the block cracks.
Scene platenBlock() {
  Scene s = notchedCrackingBlock();
  s.name = "platen-block";
  s.conditions.erase(s.conditions.begin() + 1);  // the top's velocity
  Platen top;
  top.name = "top";
  top.boxes = {{Vec2(-20.0, 100.0), Vec2(120.0, 100.0)}};
  top.dof[kPlatenX].drive = PlatenDrive::Free;
  top.dof[kPlatenY] = {PlatenDrive::Displacement, TimeFunction::linearRamp(0.018, 1.2e-4), 0.0};
  top.dof[kPlatenRotation].drive = PlatenDrive::Free;
  s.platens = {top};
  s.loads = {{"push", {Vec2(-1.0, 60.0), Vec2(3.0, 100.0)}, LoadTarget::Particles, Vec2(200.0, 0.0),
              TimeFunction::linearRamp(1.0, 5e-5)}};
  s.endTime = 1.2e-4;
  s.outputInterval = 1e-5;
  return s;
}

TEST(PlatenCheckpoint, AnExplicitRunStoppedAndResumedIsTheUninterruptedOneBitwise) {
  TempDir tmp;
  const Scene scene = platenBlock();
  const RunResult whole = runScene(scene, quiet(tmp.path() / "whole"));
  ASSERT_TRUE(whole.completed) << whole.message();
  RunOptions first = quiet(tmp.path() / "split");
  first.maxSteps = whole.steps / 2 + 3;  // between two output rows, the block cracked
  ASSERT_TRUE(runScene(scene, first).stopped);
  RunOptions second = quiet(tmp.path() / "split", 2);
  second.restart = true;
  const RunResult resumed = runScene(scene, second);
  ASSERT_TRUE(resumed.completed) << resumed.message();
  EXPECT_EQ(resumed.restartedFrom, first.maxSteps);
  EXPECT_EQ(resumed.peakLoad, whole.peakLoad);
  const nlohmann::json platens = platensOf(tmp.path() / "whole");
  ASSERT_EQ(platens.size(), 1u);
  EXPECT_GT(std::abs(platens[0]["final_displacement"][2].get<double>()), 0.0) << "the platen turned";
  EXPECT_GT(platens[0]["peak_abs_force"][1].get<double>(), 0.0);
  expectSameRun(tmp.path() / "whole", tmp.path() / "split");
}

// The coarse implicit notched beam (data/validation/beam-coarse-implicit.yaml): three platens
// (a pin, a roller, the load, each hinged), indirect control on the CMOD, tracked crack paths.
Scene beam() { return loadSceneFile(fs::path(ECM_SOURCE_DIR) / "data" / "validation" / "beam-coarse-implicit.yaml"); }

TEST(PlatenCheckpoint, AnImplicitRunStoppedAndResumedIsTheUninterruptedOneBitwise) {
  TempDir tmp;
  const Scene scene = beam();
  RunOptions options = quiet(tmp.path() / "whole");
  options.maxSteps = 40;  // past the peak (step 18): the crack runs up the ligament
  ASSERT_TRUE(runScene(scene, options).stopped);
  options.outputDir = tmp.path() / "split";
  options.maxSteps = 23;
  ASSERT_TRUE(runScene(scene, options).stopped);
  options.restart = true;
  options.maxSteps = 40;
  const RunResult resumed = runScene(scene, options);
  ASSERT_TRUE(resumed.stopped) << resumed.message();
  EXPECT_EQ(resumed.restartedFrom, 23);
  EXPECT_EQ(platensOf(tmp.path() / "whole").size(), 3u);
  expectSameRun(tmp.path() / "whole", tmp.path() / "split");
}

// ecm-mpm on a shipped scene (with `edit` applied to its text and `checkpoint` appended) killed
// with SIGKILL once its history has more than 10 rows and a checkpoint exists, then restarted
// with --restart on two threads: its history.csv, particles and summary's platens are the
// uninterrupted run's (what it wrote after its last checkpoint is cut and written again). `args`:
// extra arguments of every run (e.g. --max-steps).
void expectKilledRunRestartsBitwise(const std::string& file, const std::pair<std::string, std::string>& edit,
                                    const std::string& checkpoint, const std::vector<std::string>& args) {
  TempDir tmp;
  const fs::path source = fs::path(ECM_SOURCE_DIR) / "data" / "validation" / file;
  std::string text = readFile(source);
  const std::string material = "{file: ../materials/";
  text.replace(text.find(material), material.size(), "{file: " + (source.parent_path() / "../materials/").string());
  if (!edit.first.empty()) text.replace(text.find(edit.first), edit.first.size(), edit.second);
  text += checkpoint + "\n";
  const fs::path scene = tmp.path() / "scene.yaml";
  std::ofstream(scene) << text;
  const auto tool = [&](std::vector<std::string> a) {
    a.insert(a.end(), args.begin(), args.end());
    a.insert(a.end(), {"--no-vtu", "--no-plot", "-q"});
    const pid_t pid = fork();
    if (pid == 0) {
      std::vector<char*> argv{const_cast<char*>(ECM_MPM)};
      for (const std::string& x : a) argv.push_back(const_cast<char*>(x.c_str()));
      argv.push_back(nullptr);
      if (!freopen("/dev/null", "w", stderr) || !freopen("/dev/null", "w", stdout)) _exit(126);
      execv(ECM_MPM, argv.data());
      _exit(127);
    }
    return pid;
  };
  const auto exitStatus = [](pid_t pid) {
    int status = 0;
    waitpid(pid, &status, 0);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -WTERMSIG(status);
  };
  const std::string whole = (tmp.path() / "whole").string(), killed = (tmp.path() / "killed").string();
  const int wholeStatus = exitStatus(tool({scene.string(), "--out", whole, "--threads", "1"}));
  ASSERT_TRUE(wholeStatus == 0 || wholeStatus == 3) << wholeStatus;  // completed, or stopped at --max-steps

  const pid_t run = tool({scene.string(), "--out", killed, "--threads", "1"});
  bool checkpointed = false;
  for (int i = 0; i < 20000 && !checkpointed; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
    checkpointed = fs::exists(fs::path(killed) / "checkpoint.bin") && fs::exists(fs::path(killed) / "history.csv") &&
                   std::count(std::istreambuf_iterator<char>(std::ifstream(fs::path(killed) / "history.csv").rdbuf()),
                              std::istreambuf_iterator<char>(), '\n') > 10;
  }
  ASSERT_TRUE(checkpointed);
  kill(run, SIGKILL);
  const int status = exitStatus(run);
  if (status != -SIGKILL) GTEST_SKIP() << "the run ended (status " << status << ") before it could be killed";
  EXPECT_TRUE(fs::exists(fs::path(killed) / "checkpoint.bin"));
  EXPECT_EQ(exitStatus(tool({scene.string(), "--restart", killed, "--threads", "2"})), wholeStatus);
  expectSameRun(whole, killed);
}

// Implicit: the coarse notched beam to CMOD 0.12 mm (60 steps), checkpoints every 4 steps.
TEST(PlatenCheckpoint, AnImplicitRunKilledAndRestartedIsTheUninterruptedOneBitwise) {
  expectKilledRunRestartsBitwise("beam-coarse-implicit.yaml", {"until: 0.3}", "until: 0.12}"}, "checkpoint: {every_steps: 4}", {});
}

// Explicit: the coarse L-panel (a platen at the load point) to step 3000 (about 3 s), checkpoints
// every 250 steps.
TEST(PlatenCheckpoint, AnExplicitRunKilledAndRestartedIsTheUninterruptedOneBitwise) {
  expectKilledRunRestartsBitwise("lpanel-coarse.yaml", {}, "checkpoint: {every_steps: 250}", {"--max-steps", "3000"});
}

}  // namespace
}  // namespace ecm::mpm::test
