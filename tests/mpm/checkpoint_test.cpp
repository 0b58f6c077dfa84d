// Checkpoint and restart: a run stopped and resumed writes the same outputs as an uninterrupted
// one, bitwise; unusable checkpoints are refused with the reason; a failed write leaves the
// previous checkpoint usable; output folders that cannot be written are refused before the run
// and a full disk during it is reported without damaging what was written.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "../io/temp_dir.hpp"
#include "io/csv_reader.hpp"
#include "io/output_error.hpp"
#include "mpm/explicit/explicit_checkpoint.hpp"
#include "mpm/output/run_files.hpp"
#include "mpm/run.hpp"
#include "test_scenes.hpp"
#include "run_helpers.hpp"

namespace ecm::mpm::test {
namespace {

using namespace ecm::test;  // expectContains, FileSizeLimit, readFile, TempDir
namespace fs = std::filesystem;

// A notched block of the paper's concrete, pulled at the top by a velocity ramp and pushed
// sideways by a load on particles: it cracks within 200 steps, so the checkpoints carry band
// states, condition and load states. 1560 particles, about 290 steps, 13 output rows.
Scene crackingBlock() {
  Scene s = notchedCrackingBlock();
  s.name = "cracking-block";
  s.loads = {{"push", {Vec2(-1.0, 60.0), Vec2(3.0, 100.0)}, LoadTarget::Particles, Vec2(200.0, 0.0),
              TimeFunction::linearRamp(1.0, 5e-5)}};
  s.endTime = 1.2e-4;
  s.outputInterval = 1e-5;
  return s;
}

RunOptions options(const fs::path& dir, int threads = 1) {
  RunOptions o = quietRun(dir);
  o.snapshots = true;
  o.threads = threads;
  return o;
}

std::string bytesOf(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Every file of run `a` is in run `b` with the same bytes (summary.json aside: wall times).
void expectSameOutputs(const fs::path& a, const fs::path& b) {
  std::size_t compared = 0;
  for (const auto& entry : fs::directory_iterator(a)) {
    const std::string name = entry.path().filename().string();
    if (name == "summary.json") continue;
    ASSERT_TRUE(fs::exists(b / name)) << name;
    EXPECT_TRUE(bytesOf(entry.path()) == bytesOf(b / name)) << name << " differs";
    ++compared;
  }
  EXPECT_GE(compared, 3u);
}

template <class T>
bool sameBits(const std::vector<T>& a, const std::vector<T>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (std::memcmp(&a[i], &b[i], sizeof(T)) != 0) return false;
  return true;
}

void expectSameState(const ExplicitSolver& a, const ExplicitSolver& b) {
  const Particles &p = a.particles(), &q = b.particles();
  EXPECT_TRUE(sameBits(p.position, q.position));
  EXPECT_TRUE(sameBits(p.origin, q.origin));
  EXPECT_TRUE(sameBits(p.velocity, q.velocity));
  EXPECT_TRUE(sameBits(p.mass, q.mass));
  EXPECT_TRUE(sameBits(p.volume, q.volume));
  EXPECT_TRUE(sameBits(p.strain, q.strain));
  EXPECT_TRUE(sameBits(p.stress, q.stress));
  EXPECT_TRUE(sameBits(p.strainIncrement, q.strainIncrement));
  EXPECT_TRUE(sameBits(p.material, q.material));
  EXPECT_TRUE(sameBits(p.band, q.band));
  EXPECT_TRUE(sameBits(p.integrity, q.integrity));
  EXPECT_TRUE(sameBits(p.secondBand, q.secondBand));
  for (const auto& [x, y] : {std::pair{&p.bands, &q.bands}, std::pair{&p.secondBands, &q.secondBands}}) {
    ASSERT_EQ(x->size(), y->size());
    for (std::size_t i = 0; i < x->size(); ++i) {
      const BandState &u = (*x)[i], &v = (*y)[i];
      EXPECT_TRUE(u.crackNormal == v.crackNormal && u.jump == v.jump && u.onsetStrain == v.onsetStrain &&
                  u.integrity == v.integrity && u.volumeFraction == v.volumeFraction)
          << "band " << i;
    }
  }
  const ExplicitSolver::StepState s = a.stepState(), t = b.stepState();
  EXPECT_EQ(s.time, t.time);
  EXPECT_EQ(s.timeStep, t.timeStep);
  EXPECT_EQ(s.step, t.step);
  EXPECT_EQ(s.externalWork, t.externalWork);
  EXPECT_EQ(s.dissipated, t.dissipated);
  EXPECT_EQ(s.damping, t.damping);
  EXPECT_EQ(s.substepped, t.substepped);
  EXPECT_EQ(s.released, t.released);
  EXPECT_TRUE(sameBits(s.reactions, t.reactions));
  EXPECT_TRUE(sameBits(s.conditionDisplacements, t.conditionDisplacements));
  EXPECT_TRUE(sameBits(s.appliedLoads, t.appliedLoads));
}

TEST(Checkpoint, RestoresEveryArrayAndTheStepStateBitwise) {
  TempDir tmp;
  ExplicitSolver a(crackingBlock(), 1);
  for (int n = 0; n < 220; ++n) a.advance();
  ASSERT_GT(a.particles().bands.size(), 0u) << "the block should have cracked";
  ExplicitBookkeeping book;
  book.nextOutput = 1.1e-4;
  book.peakLoad = 1234.5;
  book.stopWatchPeak = 987.25;
  book.history = {4321, 0x1234567890abcdefull, 12};
  book.snapshotTimes = {0.0, 1e-5, 2e-5};
  const fs::path file = tmp.path() / "checkpoint.bin";
  writeExplicitCheckpoint(file, a, book, 42);
  EXPECT_FALSE(fs::exists(tmp.path() / "checkpoint.bin.tmp"));

  ExplicitSolver b(crackingBlock(), 1);
  const ExplicitBookkeeping read = readExplicitCheckpoint(file, b, 42);
  expectSameState(a, b);
  EXPECT_EQ(read.nextOutput, book.nextOutput);
  EXPECT_EQ(read.peakLoad, book.peakLoad);
  EXPECT_EQ(read.stopWatchPeak, book.stopWatchPeak);
  EXPECT_EQ(read.history.bytes, book.history.bytes);
  EXPECT_EQ(read.history.digest, book.history.digest);
  EXPECT_EQ(read.history.rows, book.history.rows);
  EXPECT_EQ(read.snapshotTimes, book.snapshotTimes);
  EXPECT_EQ(read.threads, 1);
  // And both go on identically (the per-step caches are rebuilt by the next step).
  for (int n = 0; n < 40; ++n) {
    a.advance();
    b.advance();
  }
  expectSameState(a, b);
}

// The same with the second-band option: the second bands' index and states are restored too.
TEST(Checkpoint, RestoresTheSecondBandsBitwise) {
  TempDir tmp;
  const Scene scene = twoBandBlock();
  ExplicitSolver a(scene, 1);
  while (a.particles().secondBands.empty() && a.time() < scene.endTime) a.advance();
  ASSERT_FALSE(a.particles().secondBands.empty()) << "second bands should open";
  const fs::path file = tmp.path() / "checkpoint.bin";
  writeExplicitCheckpoint(file, a, ExplicitBookkeeping{}, 42);
  ExplicitSolver b(scene, 1);
  readExplicitCheckpoint(file, b, 42);
  expectSameState(a, b);
  for (int n = 0; n < 40; ++n) {
    a.advance();
    b.advance();
  }
  expectSameState(a, b);
  // The scene without the option has no second-band index: the checkpoint does not fit.
  Scene off = scene;
  off.materials[0].secondBand = SecondBandOption::Off;
  ExplicitSolver c(off, 1);
  try {
    readExplicitCheckpoint(file, c, 42);
    FAIL() << "a checkpoint with second bands was read into a scene without them";
  } catch (const CheckpointError& e) {
    expectContains(e.what(), "second_band differs");
  }
}

// The test the whole feature is for: stopped after K steps and resumed, the outputs are the
// uninterrupted run's, byte for byte (history.csv, particles_final.csv, every snapshot, the .pvd).
TEST(Checkpoint, StopAndResumeGivesTheSameOutputsBitwise) {
  TempDir tmp;
  const Scene scene = crackingBlock();
  const RunResult whole = runScene(scene, options(tmp.path() / "whole"));
  ASSERT_TRUE(whole.completed) << whole.message();
  ASSERT_GT(whole.steps, 250);

  RunOptions first = options(tmp.path() / "split");
  first.maxSteps = 137;  // between two output rows, after the onset of cracking
  const RunResult stopped = runScene(scene, first);
  EXPECT_FALSE(stopped.completed);
  ASSERT_TRUE(stopped.stopped) << stopped.message();
  EXPECT_EQ(stopped.steps, 137);
  EXPECT_EQ(stopped.checkpoint, tmp.path() / "split" / "checkpoint.bin");
  const auto summary = nlohmann::json::parse(readFile(tmp.path() / "split" / "summary.json"));
  EXPECT_EQ(summary["status"], "stopped");
  EXPECT_EQ(summary["checkpoint_step"], 137);

  RunOptions second = options(tmp.path() / "split");
  second.restart = true;
  const RunResult resumed = runScene(scene, second);
  ASSERT_TRUE(resumed.completed) << resumed.message();
  EXPECT_EQ(resumed.restartedFrom, 137);
  EXPECT_EQ(resumed.steps, whole.steps);
  EXPECT_EQ(resumed.peakLoad, whole.peakLoad);
  EXPECT_FALSE(fs::exists(tmp.path() / "split" / "checkpoint.bin")) << "a completed run removes its checkpoint";
  fs::remove(tmp.path() / "whole" / "summary.json");
  expectSameOutputs(tmp.path() / "whole", tmp.path() / "split");
  const auto j = nlohmann::json::parse(readFile(tmp.path() / "split" / "summary.json"));
  EXPECT_EQ(j["status"], "completed");
  EXPECT_EQ(j["restarted_from_step"], 137);
  EXPECT_EQ(j["steps"], whole.steps);
}

// The same with tracked crack paths (docs/model.md, "Crack paths"): the checkpoint holds the paths,
// so the resumed run opens its bands where the uninterrupted one does (crack_paths.csv included).
TEST(Checkpoint, StopAndResumeWithTrackedCrackPathsGivesTheSameOutputsBitwise) {
  TempDir tmp;
  Scene scene = crackingBlock();
  scene.solver.crackPath = CrackPathRule::Tracked;
  const RunResult whole = runScene(scene, options(tmp.path() / "whole"));
  ASSERT_TRUE(whole.completed) << whole.message();
  ASSERT_TRUE(fs::exists(tmp.path() / "whole" / "crack_paths.csv"));
  RunOptions first = options(tmp.path() / "split");
  first.maxSteps = 137;
  ASSERT_TRUE(runScene(scene, first).stopped);
  RunOptions second = options(tmp.path() / "split");
  second.restart = true;
  const RunResult resumed = runScene(scene, second);
  ASSERT_TRUE(resumed.completed) << resumed.message();
  fs::remove(tmp.path() / "whole" / "summary.json");
  expectSameOutputs(tmp.path() / "whole", tmp.path() / "split");
}

// history.csv of a tracked run ends with what the rule holds intact off the paths
// (docs/model.md, "Crack paths"): the points past onset, sqrt(Y / Y_onset) >= 1 by definition, and
// the largest of those overstresses (0 where none is held). The block's growing crack holds the
// points beside its path. A run under the free rule holds nothing and has no such columns.
TEST(Checkpoint, ATrackedRunCountsThePointsItHoldsPastOnset) {
  TempDir tmp;
  Scene scene = crackingBlock();
  scene.solver.crackPath = CrackPathRule::Tracked;
  ASSERT_TRUE(runScene(scene, options(tmp.path() / "tracked")).completed);
  const io::CsvTable h = io::readCsv(tmp.path() / "tracked" / "history.csv");
  ASSERT_GE(h.header.size(), 2u);
  const std::size_t count = h.header.size() - 2, largest = h.header.size() - 1;
  EXPECT_EQ(h.header[count], "held_past_onset");
  EXPECT_EQ(h.header[largest], "held_max_overstress");
  std::size_t rowsHolding = 0;
  for (const auto& row : h.rows) {
    EXPECT_EQ(row[count], std::floor(row[count]));
    if (row[count] == 0.0) {
      EXPECT_EQ(row[largest], 0.0);
    } else {
      EXPECT_GE(row[largest], 1.0);
      ++rowsHolding;
    }
  }
  EXPECT_GT(rowsHolding, 0u);
  scene.solver.crackPath = CrackPathRule::Free;
  ASSERT_TRUE(runScene(scene, options(tmp.path() / "free")).completed);
  const io::CsvTable f = io::readCsv(tmp.path() / "free" / "history.csv");
  EXPECT_EQ(std::count(f.header.begin(), f.header.end(), "held_past_onset"), 0);
  EXPECT_EQ(f.header.size(), h.header.size() - 2);
}

// With snapshot_every N the restarted run goes on with the same snapshot rows: the split run's
// folder holds exactly the uninterrupted run's files, byte for byte (13 history rows, snapshots
// at rows 0, 4, 8, 12).
TEST(Checkpoint, StopAndResumeKeepsTheSnapshotRows) {
  TempDir tmp;
  Scene scene = crackingBlock();
  scene.snapshotEvery = 4;
  const RunResult whole = runScene(scene, options(tmp.path() / "whole"));
  ASSERT_TRUE(whole.completed) << whole.message();
  RunOptions first = options(tmp.path() / "split");
  first.maxSteps = 137;  // between output rows 5 and 6
  ASSERT_TRUE(runScene(scene, first).stopped);
  RunOptions second = options(tmp.path() / "split");
  second.restart = true;
  ASSERT_TRUE(runScene(scene, second).completed);
  fs::remove(tmp.path() / "whole" / "summary.json");
  expectSameOutputs(tmp.path() / "whole", tmp.path() / "split");
  std::size_t vtu = 0, files = 0;
  for (const auto& e : fs::directory_iterator(tmp.path() / "split")) {
    ++files;
    vtu += e.path().extension() == ".vtu" ? 1 : 0;
  }
  EXPECT_EQ(vtu, 4u);
  EXPECT_EQ(files, std::size_t(std::distance(fs::directory_iterator(tmp.path() / "whole"), fs::directory_iterator{})) + 1)
      << "the split folder has the whole run's files and summary.json, nothing more";
}

// A stop request (the flag a SIGINT / SIGTERM handler sets) is honoured after the step in
// progress; here it is set before the start, so the run stops at step 0 with a checkpoint.
TEST(Checkpoint, StopFlagStopsWithACheckpointAndTheResumeMatches) {
  TempDir tmp;
  Scene scene = crackingBlock();
  scene.endTime = 4e-5;
  const RunResult whole = runScene(scene, options(tmp.path() / "whole"));
  ASSERT_TRUE(whole.completed) << whole.message();

  std::atomic<bool> stop{true};
  RunOptions first = options(tmp.path() / "split");
  first.stop = &stop;
  first.resumeCommand = "ecm-mpm block.yaml --restart split";
  const RunResult stopped = runScene(scene, first);
  ASSERT_TRUE(stopped.stopped);
  EXPECT_EQ(stopped.steps, 0);
  EXPECT_EQ(nlohmann::json::parse(readFile(tmp.path() / "split" / "summary.json"))["resume"],
            "ecm-mpm block.yaml --restart split");
  stop = false;
  RunOptions second = first;
  second.restart = true;
  ASSERT_TRUE(runScene(scene, second).completed);
  EXPECT_EQ(bytesOf(tmp.path() / "whole" / "history.csv"), bytesOf(tmp.path() / "split" / "history.csv"));
  EXPECT_EQ(bytesOf(tmp.path() / "whole" / "particles_final.csv"),
            bytesOf(tmp.path() / "split" / "particles_final.csv"));
}

// A crash after a periodic checkpoint leaves history rows (and snapshots) the checkpoint does not
// know: the resume cuts them off and writes them again, so there are no duplicates.
TEST(Checkpoint, ResumeCutsRowsWrittenAfterTheCheckpoint) {
  TempDir tmp;
  Scene scene = crackingBlock();
  const RunResult whole = runScene(scene, options(tmp.path() / "whole"));
  ASSERT_TRUE(whole.completed) << whole.message();

  scene.checkpoint.everySteps = 60;
  const fs::path dir = tmp.path() / "crash";
  RunOptions o = options(dir);
  o.maxSteps = 120;
  ASSERT_TRUE(runScene(scene, o).stopped);
  fs::copy_file(dir / "checkpoint.bin", tmp.path() / "step120.bin");
  o.restart = true;
  o.maxSteps = 230;  // periodic checkpoints at 180, then a stop at 230: rows and snapshots past step 120
  const RunResult later = runScene(scene, o);
  ASSERT_TRUE(later.stopped);
  EXPECT_EQ(later.checkpoints, 2);
  const auto rowsAt230 = io::readCsv(dir / "history.csv").rows.size();
  fs::copy_file(tmp.path() / "step120.bin", dir / "checkpoint.bin", fs::copy_options::overwrite_existing);
  o.maxSteps = 0;
  const RunResult resumed = runScene(scene, o);  // as if the run had died just before step 230
  ASSERT_TRUE(resumed.completed) << resumed.message();
  EXPECT_EQ(resumed.restartedFrom, 120);
  EXPECT_GT(rowsAt230, io::readCsv(tmp.path() / "whole" / "history.csv").rows.size() / 2);
  fs::remove(tmp.path() / "whole" / "summary.json");
  expectSameOutputs(tmp.path() / "whole", dir);
}

// The same scene run twice on one thread gives the same history and particles, bitwise.
TEST(Determinism, RunTwiceGivesTheSameHistoryBitwise) {
  TempDir tmp;
  const Scene scene = crackingBlock();
  ASSERT_TRUE(runScene(scene, options(tmp.path() / "a")).completed);
  ASSERT_TRUE(runScene(scene, options(tmp.path() / "b")).completed);
  fs::remove(tmp.path() / "a" / "summary.json");
  expectSameOutputs(tmp.path() / "a", tmp.path() / "b");
}

// A run stopped on two threads and resumed on one has the outputs of the uninterrupted run on
// two, bitwise: every node sums its particles in an order set by the particles alone
// (mpm/explicit/scatter_order.hpp; the checkpoint keeps the blocks the fused pass scattered from), every
// sum over particles or nodes is taken in fixed chunks (the dissipation per chunk of the dynamic
// schedule, mpm/explicit/stress_update.cpp; the others by mpm/core/ordered_sum.hpp), whichever thread took
// which chunk and however many there are.
TEST(Determinism, StopOnTwoThreadsAndResumeOnOne) {
  TempDir tmp;
  Scene scene = crackingBlock();
  scene.endTime = 6e-5;  // about 145 steps: two threads on a busy machine are slow
  ASSERT_TRUE(runScene(scene, options(tmp.path() / "whole", 2)).completed);
  RunOptions o = options(tmp.path() / "split", 2);
  o.maxSteps = 100;
  ASSERT_TRUE(runScene(scene, o).stopped);
  o.restart = true;
  o.maxSteps = 0;
  o.threads = 1;
  ASSERT_TRUE(runScene(scene, o).completed);
  const fs::path a = tmp.path() / "whole", b = tmp.path() / "split";
  EXPECT_EQ(bytesOf(a / "particles_final.csv"), bytesOf(b / "particles_final.csv"));
  EXPECT_EQ(bytesOf(a / "particles_00006.vtu"), bytesOf(b / "particles_00006.vtu"));
  EXPECT_EQ(bytesOf(a / "particles.pvd"), bytesOf(b / "particles.pvd"));
  EXPECT_EQ(bytesOf(a / "history.csv"), bytesOf(b / "history.csv"));
  const io::CsvTable x = io::readCsv(a / "history.csv");
  const std::vector<std::string> columns = historyColumns(scene);
  const auto dissipated =
      static_cast<std::size_t>(std::find(columns.begin(), columns.end(), "dissipated_Nmm") - columns.begin());
  EXPECT_GT(x.rows.back()[dissipated], 0.0) << "the block should have cracked: the test would not see the sum";
}

// --- refusals -----------------------------------------------------------------------------

std::string refusal(const fs::path& file, std::uint64_t sceneHash = 0, const Scene& scene = crackingBlock()) {
  ExplicitSolver s(scene, 1);
  try {
    readExplicitCheckpoint(file, s, sceneHash);
  } catch (const CheckpointError& e) {
    expectContains(e.what(), file.string());
    return e.what();
  }
  ADD_FAILURE() << "checkpoint " << file << " was accepted";
  return "";
}

TEST(Checkpoint, RefusesMissingTruncatedCorruptedForeignOrOtherVersionFiles) {
  TempDir tmp;
  ExplicitSolver a(crackingBlock(), 1);
  for (int n = 0; n < 150; ++n) a.advance();
  const fs::path good = tmp.path() / "good.bin";
  writeExplicitCheckpoint(good, a, {}, 7);
  const std::string bytes = bytesOf(good);
  auto variant = [&](const std::string& name, const std::string& content) {
    std::ofstream(tmp.path() / name, std::ios::binary) << content;
    return tmp.path() / name;
  };
  expectContains(refusal(tmp.path() / "none.bin", 7), "no such file");
  expectContains(refusal(variant("short.bin", bytes.substr(0, bytes.size() / 2)), 7), "truncated");
  expectContains(refusal(variant("header.bin", bytes.substr(0, 20)), 7), "truncated");
  std::string flipped = bytes;
  flipped[bytes.size() / 2] ^= 0x10;
  expectContains(refusal(variant("flipped.bin", flipped), 7), "corrupted (checksum mismatch)");
  expectContains(refusal(variant("long.bin", bytes + "x"), 7), "corrupted");
  expectContains(refusal(variant("foreign.bin", "# a text file, not a checkpoint\n"), 7), "not an ecm-mpm checkpoint");
  std::string version = bytes;
  version[8] = static_cast<char>(kCheckpointVersion + 1);  // the u32 after the signature
  expectContains(refusal(variant("next.bin", version), 7),
                 "format version " + std::to_string(kCheckpointVersion + 1) + "; this ecm-mpm reads version " +
                     std::to_string(kCheckpointVersion));
  // Another scene file (hash), and a scene whose particles do not match.
  expectContains(refusal(good, 8), "written for another scene file");
  Scene other = crackingBlock();
  other.bodies.pop_back();  // no notch: more particles
  expectContains(refusal(good, 7, other), "particles, the scene");
  // The good one is accepted.
  ExplicitSolver b(crackingBlock(), 1);
  EXPECT_NO_THROW(readExplicitCheckpoint(good, b, 7));
}

TEST(Checkpoint, RestartRefusesAChangedHistoryAndTouchesNothing) {
  TempDir tmp;
  const Scene scene = crackingBlock();
  RunOptions o = options(tmp.path() / "run");
  o.maxSteps = 100;
  ASSERT_TRUE(runScene(scene, o).stopped);
  const fs::path history = tmp.path() / "run" / "history.csv";
  std::string text = bytesOf(history);
  text[text.size() - 3] = text[text.size() - 3] == '1' ? '2' : '1';
  std::ofstream(history, std::ios::binary) << text;
  o.restart = true;
  o.maxSteps = 0;
  try {
    runScene(scene, o);
    FAIL() << "a changed history.csv was accepted";
  } catch (const CheckpointError& e) {
    expectContains(e.what(), "history.csv");
    expectContains(e.what(), "were changed");
  }
  EXPECT_EQ(bytesOf(history), text);
  // A different scene (hash) is refused before anything is written, too.
  o.sceneHash = 99;
  EXPECT_THROW(runScene(scene, o), CheckpointError);
}

// --- atomic writes and full disks ------------------------------------------------------------

TEST(Checkpoint, FailedWriteKeepsThePreviousCheckpointUsable) {
  TempDir tmp;
  const Scene scene = crackingBlock();
  const fs::path dir = tmp.path() / "run";
  RunOptions o = options(dir);
  o.snapshots = false;
  ASSERT_TRUE(runScene(scene, options(tmp.path() / "whole")).completed);
  o.maxSteps = 100;
  ASSERT_TRUE(runScene(scene, o).stopped);
  const std::string before = bytesOf(dir / "checkpoint.bin");
  ASSERT_GT(before.size(), 100000u);
  o.restart = true;
  o.maxSteps = 150;
  RunResult failed;
  {
    const FileSizeLimit limit(50000);  // history.csv and summary.json fit, a checkpoint does not
    failed = runScene(scene, o);
  }
  EXPECT_FALSE(failed.completed);
  EXPECT_FALSE(failed.stopped);
  ASSERT_TRUE(failed.failure);
  EXPECT_EQ(failed.failure->kind, FailureKind::Output);
  EXPECT_EQ(failed.failure->file, dir / "checkpoint.bin") << failed.message();
  EXPECT_EQ(bytesOf(dir / "checkpoint.bin"), before);
  EXPECT_FALSE(fs::exists(dir / "checkpoint.bin.tmp"));
  const auto summary = nlohmann::json::parse(readFile(dir / "summary.json"));
  EXPECT_EQ(summary["status"], "failed");
  EXPECT_EQ(summary["checkpoint_step"], 100);
  // The old checkpoint still gives the uninterrupted run's history.
  o.maxSteps = 0;
  o.snapshots = true;
  ASSERT_TRUE(runScene(scene, o).completed);
  EXPECT_EQ(bytesOf(tmp.path() / "whole" / "history.csv"), bytesOf(dir / "history.csv"));
}

TEST(RunOutput, FullDiskMidRunIsReportedAndTheHistoryEndsWithAWholeRow) {
  TempDir tmp;
  const fs::path dir = tmp.path() / "run";
  RunOptions o = options(dir);
  o.snapshots = false;
  RunResult r;
  {
    const FileSizeLimit limit(2500);  // a few rows of history.csv
    r = runScene(crackingBlock(), o);
  }
  EXPECT_FALSE(r.completed);
  ASSERT_TRUE(r.failure);
  EXPECT_EQ(r.failure->kind, FailureKind::Output);
  EXPECT_EQ(r.failure->file, dir / "history.csv") << r.message();
  EXPECT_EQ(nlohmann::json::parse(readFile(dir / "summary.json"))["failure"]["kind"], "output");
  const std::string history = bytesOf(dir / "history.csv");
  EXPECT_LE(history.size(), 2500u);
  ASSERT_FALSE(history.empty());
  EXPECT_EQ(history.back(), '\n');
  const io::CsvTable t = io::readCsv(dir / "history.csv");  // every row whole
  EXPECT_GE(t.rows.size(), 2u);
  const auto summary = nlohmann::json::parse(readFile(dir / "summary.json"));
  EXPECT_EQ(summary["status"], "failed");
  expectContains(summary["error"].get<std::string>(), "history.csv");
}

TEST(RunOutput, FolderThatCannotBeWrittenIsRefusedBeforeTheRun) {
  TempDir tmp;
  const fs::path file = tmp.write("plain.txt", "x");
  for (const fs::path& bad : {file, file / "out"}) {
    try {
      runScene(crackingBlock(), options(bad));
      FAIL() << "no error for " << bad;
    } catch (const io::OutputError& e) {
      expectContains(e.what(), bad.string());
    }
  }
  if (::geteuid() == 0) GTEST_SKIP() << "running as root: permissions do not stop root";
  const fs::path locked = tmp.path() / "locked";
  fs::create_directories(locked);
  fs::permissions(locked, fs::perms::owner_read | fs::perms::owner_exec);
  for (const fs::path& bad : {locked, locked / "out"}) {
    try {
      runScene(crackingBlock(), options(bad));
      FAIL() << "no error for " << bad;
    } catch (const io::OutputError& e) {
      expectContains(e.what(), bad.string());
    }
  }
  fs::permissions(locked, fs::perms::owner_all);
  EXPECT_TRUE(fs::is_empty(locked));
}

}  // namespace
}  // namespace ecm::mpm::test
