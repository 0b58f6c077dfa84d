// implicit_static scenes: the shipped bar read and run through runScene (the path ecm-mpm and
// the Python module take), with its energy balance; and the refusals of bad input with the line
// and the reason.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <sstream>
#include <nlohmann/json.hpp>

#include "../io/temp_dir.hpp"
#include "run_helpers.hpp"
#include "test_scenes.hpp"
#include "mpm/explicit/explicit_checkpoint.hpp"
#include "mpm/run.hpp"
#include "mpm/scene/scene_yaml.hpp"

namespace ecm::mpm::test {
namespace {

using namespace ecm::test;  // expectContains, inputError

std::string shippedBar() {
  std::ifstream in(std::filesystem::path(ECM_SOURCE_DIR) / "data" / "mpm" / "bar-snapback-implicit.yaml");
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

TEST(ImplicitScene, TheShippedBarRunsThroughItsPeakWithItsEnergyBalanced) {
  // The first 0.002 mm of opening (200 load steps): through the peak at 9.1e-4 mm.
  const std::string text = replaced(shippedBar(), "until: 0.04 ", "until: 0.002");
  const Scene scene = readScene(io::parseYaml(text, "bar.yaml"));
  ASSERT_TRUE(scene.solver.implicit && scene.solver.implicit->indirect);
  ecm::test::TempDir dir;
  RunOptions options = quietRun(dir.path() / "out");
  options.snapshots = true;
  const RunResult r = runScene(scene, options);
  ASSERT_TRUE(r.completed) << r.message();
  EXPECT_EQ(r.steps, 200);
  // The peak: the weak row's strength times the bar's section (20 mm x 1 mm), to 1e-3.
  EXPECT_NEAR(r.peakLoad, 2.9 * 20.0, 1e-3 * 2.9 * 20.0);
  // The external work is what is stored plus what the band dissipated (last row).
  std::ifstream in(options.outputDir / "history.csv");
  std::string header, line, last;
  std::getline(in, header);
  while (std::getline(in, line)) last = line;
  std::vector<std::string> names, values;
  for (std::stringstream h(header); std::getline(h, line, ',');) names.push_back(line);
  for (std::stringstream v(last); std::getline(v, line, ',');) values.push_back(line);
  ASSERT_EQ(names.size(), values.size());
  const auto at = [&](const std::string& name) {
    return std::stod(values[static_cast<std::size_t>(std::find(names.begin(), names.end(), name) - names.begin())]);
  };
  EXPECT_GT(at("dissipated_Nmm"), 0.0);
  EXPECT_NEAR(at("external_work_Nmm"), at("strain_Nmm") + at("dissipated_Nmm"), 1e-3 * at("external_work_Nmm"));
  EXPECT_GT(at("load_factor"), 0.0);
  EXPECT_TRUE(std::filesystem::exists(options.outputDir / "particles_final.csv"));
  EXPECT_TRUE(std::filesystem::exists(options.outputDir / "summary.json"));
}

TEST(ImplicitScene, BadInputIsRefusedWithTheLineAndTheReason) {
  const std::string bar = shippedBar();
  const auto err = [](const std::string& text) { return inputError([&] { readScene(io::parseYaml(text, "bar.yaml")); }); };
  {  // an explicit-only key on an implicit scene
    const auto e = err(replaced(bar, "  tolerance: 1e-6 ", "  cfl: 0.3\n  tolerance: 1e-6 "));
    expectContains(e.what(), "cfl");
    expectContains(e.what(), "explicit");
  }
  {  // an implicit key on an explicit scene
    const auto e = err(replaced(replaced(bar, "  scheme: implicit_static", "  scheme: usl"), "  control:", "  control_:"));
    expectContains(e.what(), "tolerance");
    expectContains(e.what(), "implicit_static");
  }
  {  // a driven condition that does not exist
    const auto e = err(replaced(bar, "driven: [top]", "driven: [roof]"));
    expectContains(e.what(), "no condition or platen named 'roof'");
    EXPECT_EQ(e.line, 29);
  }
  {  // a control that names no node
    const std::string text = bar.substr(0, bar.find("      opening:")) + "      opening: []\n" + bar.substr(bar.find("      step: 1e-5"));
    expectContains(err(text).what(), "names no node");
  }
  {  // a tolerance out of range
    const auto e = err(replaced(bar, "tolerance: 1e-6 ", "tolerance: 0.5 "));
    expectContains(e.what(), "tolerance");
    EXPECT_EQ(e.line, 26);
  }
  {  // an accept_tolerance below the tolerance; without one, a loose tolerance is its own
    expectContains(err(replaced(bar, "tolerance: 1e-6 ", "tolerance: 1e-4\n  accept_tolerance: 1e-5 ")).what(),
                   "accept_tolerance");
    const Scene loose = readScene(io::parseYaml(replaced(bar, "tolerance: 1e-6 ", "tolerance: 5e-3 "), "bar.yaml"));
    EXPECT_EQ(loose.solver.implicit->acceptTolerance, 5e-3);
  }
  {  // a stabilization out of [0, 1], or not a number, on its own line (27)
    for (const char* value : {"1.5", "-0.01", "yes"}) {
      const auto e = err(replaced(bar, "tolerance: 1e-6 ", std::string("tolerance: 1e-6\n  stabilization: ") + value + " "));
      expectContains(e.what(), "solver.stabilization");
      EXPECT_EQ(e.line, 27) << value;
    }
  }
}

std::string fileText(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// A run stopped (with its checkpoint) and restarted on another thread count writes the
// uninterrupted run's history.csv and particles, bitwise: the checkpoint holds the solver's
// adaptive piece, the last step's geometry and the tangent it last factorised.
// Returns the uninterrupted run's history.csv.
std::string expectRestartIsBitwise(const Scene& scene, long stopAt, long end) {
  ecm::test::TempDir dir;
  RunOptions options = quietRun(dir.path() / "whole");
  options.sceneHash = 42;
  options.maxSteps = end;
  const RunResult whole = runScene(scene, options);
  EXPECT_TRUE(whole.stopped) << whole.message();
  options.outputDir = dir.path() / "parts";
  options.maxSteps = stopAt;
  const RunResult first = runScene(scene, options);
  EXPECT_TRUE(first.stopped) << first.message();
  EXPECT_TRUE(std::filesystem::exists(options.outputDir / "checkpoint.bin"));
  options.restart = true;
  options.threads = 2;
  options.maxSteps = end;
  const RunResult second = runScene(scene, options);
  EXPECT_TRUE(second.stopped) << second.message();
  EXPECT_EQ(second.restartedFrom, stopAt);
  EXPECT_EQ(second.steps, end);
  EXPECT_EQ(fileText(dir.path() / "whole" / "history.csv"), fileText(dir.path() / "parts" / "history.csv"));
  EXPECT_EQ(fileText(dir.path() / "whole" / "particles_final.csv"), fileText(dir.path() / "parts" / "particles_final.csv"));

  // A checkpoint of another scene is refused.
  options.sceneHash = 43;
  try {
    runScene(scene, options);
    ADD_FAILURE() << "a checkpoint of another scene was taken";
  } catch (const CheckpointError& e) {
    expectContains(e.what(), "another scene");
  }
  return fileText(dir.path() / "whole" / "history.csv");
}

TEST(ImplicitScene, AStoppedIndirectRunRestartsBitwiseOnAnotherThreadCount) {
  // The bar through its peak (at step 91) under indirect control, stopped at 120 of 160.
  const Scene scene = readScene(io::parseYaml(replaced(shippedBar(), "until: 0.04 ", "until: 0.002"), "bar.yaml"));
  expectRestartIsBitwise(scene, 120, 160);
}

// The bar under displacement control jumps its snap-back in a stabilised step, load step 77
// (docs/implicit.md, "Stabilised steps"): a run stopped before it and one stopped after it both
// restart bitwise, the energy its dashpots took (damping_Nmm) carried by the checkpoint.
TEST(ImplicitScene, AStabilisedStepRestartsBitwiseStoppedBeforeOrAfterIt) {
  const std::string bar = shippedBar();
  std::string text = bar.substr(0, bar.find("  control:")) + "  load_step: 0.01\n  max_halvings: 4\n" + bar.substr(bar.find("end_time:"));
  text = replaced(text, "displacement: {y: {type: hold, value: 0}}", "displacement: {y: {type: linear_ramp, value: 0.12, time: 1}}");
  const Scene scene = readScene(io::parseYaml(text, "bar.yaml"));
  expectRestartIsBitwise(scene, 70, 90);
  const std::string history = expectRestartIsBitwise(scene, 80, 90);
  // The jump is in it: one row with proximal steps, and the dashpots' energy from there on.
  std::stringstream in(history);
  std::string line;
  std::getline(in, line);
  EXPECT_NE(line.find("damping_Nmm"), std::string::npos);
  ASSERT_EQ(line.substr(line.rfind(',') + 1), "proximal_steps");
  int jumps = 0;
  while (std::getline(in, line))
    if (std::stod(line.substr(line.rfind(',') + 1)) > 0.0) ++jumps;
  EXPECT_EQ(jumps, 1);
}

// The same with tracked crack paths: the checkpoint holds them (the DEN coarse cracks from step 40).
// Its history.csv ends with what the rule holds intact past onset (docs/model.md, "Crack paths"),
// noted by the implicit solver after each step: a whole count, and sqrt(Y / Y_onset) >= 1 of the
// most overstressed held point (0 where none is held); the DEN holds points by step 60.
TEST(ImplicitScene, AStoppedRunWithTrackedCrackPathsRestartsBitwise) {
  Scene scene = loadSceneFile(std::filesystem::path(ECM_SOURCE_DIR) / "data" / "den" / "den-4b-coarse-implicit.yaml");
  scene.solver.crackPath = CrackPathRule::Tracked;
  const std::string history = expectRestartIsBitwise(scene, 45, 60);
  std::stringstream in(history);
  std::string line;
  std::getline(in, line);
  ASSERT_EQ(line.substr(line.rfind(',') + 1), "held_max_overstress");
  ASSERT_NE(line.find(",held_past_onset,held_max_overstress"), std::string::npos);
  int rowsHolding = 0;
  while (std::getline(in, line)) {
    const double largest = std::stod(line.substr(line.rfind(',') + 1));
    const std::string rest = line.substr(0, line.rfind(','));
    const double count = std::stod(rest.substr(rest.rfind(',') + 1));
    EXPECT_EQ(count, std::floor(count));
    if (count == 0.0) {
      EXPECT_EQ(largest, 0.0);
    } else {
      EXPECT_GE(largest, 1.0);
      ++rowsHolding;
    }
  }
  EXPECT_GT(rowsHolding, 0);
}

TEST(ImplicitScene, AStoppedDisplacementControlledRunRestartsBitwiseOnAnotherThreadCount) {
  // The DEN coarse: the shear ramp and the first steps of tension, cracking from step 40 on.
  const Scene scene = loadSceneFile(std::filesystem::path(ECM_SOURCE_DIR) / "data" / "den" / "den-4b-coarse-implicit.yaml");
  const std::string history = expectRestartIsBitwise(scene, 45, 60);
  // Equilibrium after every step: the reactions of the three conditions balance the shear load,
  // to the Newton tolerance (1e-6 of the forces; measured over the whole run: 1.3e-7 of P).
  std::stringstream in(history);
  std::string line;
  std::getline(in, line);
  int rows = 0;
  while (std::getline(in, line)) {
    std::vector<double> v;
    for (std::stringstream row(line); std::getline(row, line, ',');) v.push_back(std::stod(line));
    // Columns: time, step, then (ux, uy, rx, ry) of bottom, right-lower, top, then the shear load.
    const double sumX = v[4] + v[8] + v[12] + v[14], sumY = v[5] + v[9] + v[13] + v[15];
    const double scale = std::max({std::abs(v[14]), std::abs(v[13]), 1.0});
    EXPECT_LT(std::abs(sumX), 1e-6 * scale) << "row " << rows;
    EXPECT_LT(std::abs(sumY), 1e-6 * scale) << "row " << rows;
    ++rows;
  }
  EXPECT_EQ(rows, 61);
}

// A tolerance below round-off cannot be met: Newton stalls near 1e-13. With accept_tolerance
// above that floor every step is kept and counted as relaxed (each looks hard, so the steps
// shrink to the smallest); at the tolerance itself the run stops loudly, naming the step and
// the residual. (Two iterations and two halvings keep it short.)
TEST(ImplicitScene, AStalledNewtonIsKeptBelowTheAcceptToleranceAndStopsTheRunAboveIt) {
  const std::string bar = replaced(replaced(shippedBar(), "until: 0.04 ", "until: 0.0002"),  // 20 elastic steps or more
                                   "  control:", "  max_iterations: 2\n  max_halvings: 2\n  control:");
  ecm::test::TempDir dir;
  RunOptions options = quietRun({});  // each run below names its folder
  {
    const Scene scene = readScene(io::parseYaml(replaced(bar, "tolerance: 1e-6 ", "tolerance: 1e-16\n  accept_tolerance: 1e-9"), "bar.yaml"));
    options.outputDir = dir.path() / "kept";
    const RunResult r = runScene(scene, options);
    EXPECT_TRUE(r.completed) << r.message();
    const std::string summary = fileText(options.outputDir / "summary.json");
    EXPECT_GE(r.steps, 20);
    expectContains(summary, "\"relaxed_steps\": " + std::to_string(r.steps) + ",");
  }
  {
    const Scene scene = readScene(io::parseYaml(replaced(bar, "tolerance: 1e-6 ", "tolerance: 1e-16\n  accept_tolerance: 1e-16"), "bar.yaml"));
    options.outputDir = dir.path() / "stopped";
    const RunResult r = runScene(scene, options);
    EXPECT_FALSE(r.completed);
    ASSERT_TRUE(r.failure);
    EXPECT_EQ(r.failure->kind, FailureKind::NewtonNotConverged);
    EXPECT_EQ(r.failure->step, 1);
    EXPECT_FALSE(r.failure->likelyLimitPoint);  // nothing cracked: no structural limit point
    EXPECT_EQ(nlohmann::json::parse(fileText(options.outputDir / "summary.json"))["failure"]["kind"], "newton_not_converged");
    EXPECT_TRUE(std::filesystem::exists(options.outputDir / "history.csv"));
  }
}

// Newton proper that stalls (here at round-off, below an unreachable tolerance) is given up after
// its residual did not halve over 6 iterations, not after max_iterations (docs/implicit.md,
// "Load steps"): a step is the first try's max_iterations (kept factorisation) plus 1, then at
// most 8 or so for Newton proper, against 2 x 101 without the test.
TEST(ImplicitScene, AStalledNewtonProperIsGivenUpEarly) {
  const std::string bar = replaced(replaced(shippedBar(), "until: 0.04 ", "until: 0.0002"), "  control:", "  max_iterations: 60\n  control:");
  ecm::test::TempDir dir;
  RunOptions options = quietRun(dir.path() / "kept");
  const Scene scene = readScene(io::parseYaml(replaced(bar, "tolerance: 1e-6 ", "tolerance: 1e-16\n  accept_tolerance: 1e-9"), "bar.yaml"));
  const RunResult r = runScene(scene, options);
  ASSERT_TRUE(r.completed) << r.message();
  const std::string summary = fileText(options.outputDir / "summary.json");
  expectContains(summary, "\"relaxed_steps\": " + std::to_string(r.steps) + ",");
  const auto at = summary.find("\"most_newton_iterations_in_a_step\": ");
  ASSERT_NE(at, std::string::npos);
  const int most = std::stoi(summary.substr(at + std::string("\"most_newton_iterations_in_a_step\": ").size()));
  EXPECT_GT(most, 61);  // the first try ran to max_iterations
  EXPECT_LT(most, 61 + 15);
}

TEST(ImplicitScene, VtuSnapshotsFollowTheOutputIntervalInTheProgressUnit) {
  // Under indirect control the progress is the opening (mm): a snapshot at 0, 0.0005, ... 0.002.
  const Scene scene = readScene(io::parseYaml(replaced(shippedBar(), "until: 0.04 ", "until: 0.002") +
                                                  "output_interval: 0.0005\n", "bar.yaml"));
  ecm::test::TempDir dir;
  RunOptions options = quietRun(dir.path() / "out");
  options.snapshots = true;
  const RunResult r = runScene(scene, options);
  ASSERT_TRUE(r.completed) << r.message();
  for (int k = 0; k < 5; ++k) EXPECT_TRUE(std::filesystem::exists(options.outputDir / ("particles_0000" + std::to_string(k) + ".vtu"))) << k;
  EXPECT_FALSE(std::filesystem::exists(options.outputDir / "particles_00005.vtu"));
  expectContains(fileText(options.outputDir / "particles.pvd"), "timestep=\"0.002\"");
}

// The scene's snap_back acts in implicit runs as in explicit ones. The weak row softens with
// E_p = 400 MPa: its points snap back at H = 10 mm (the material's snap-back size
// h (E + E_p) / E_p = 0.05 x 32400 / 400 = 4.05 mm < H; docs/model.md, "Snap-back on the path").
// With release (the default) the band fails onto its stable branch and the run goes on, counted,
// with no halving spent on it (docs/implicit.md, "Load steps"), and the weak row dissipates its
// fracture energy: G_F A = 0.00119699 N/mm x 20 mm^2 = 0.0239399 N mm (G_F from
// `ecm-calibrate --E 32000 --ft 2.9 --h 0.05 --Ep 400 --n 0.128`, the forward mode; at the
// run's last opening the band is not quite failed, 4e-5 of it short). With stop the run ends at
// the first snap-back that persists after a halving, naming the point.
TEST(ImplicitScene, SnapBackReleaseGoesOnAndStopEndsTheRunAtThePoint) {
  const std::string weak = replaced(replaced(shippedBar(), "until: 0.04 ", "until: 0.004"),
                                    "tensile_strength: 2.9, softening_modulus: 8.184", "tensile_strength: 2.9, softening_modulus: 400");
  ecm::test::TempDir dir;
  {
    const Scene scene = readScene(io::parseYaml(weak, "bar.yaml"));
    ASSERT_EQ(scene.solver.snapBack, SnapBackPolicy::Release);
    const RunResult r = runScene(scene, quietRun(dir.path() / "release"));
    ASSERT_TRUE(r.completed) << r.message();
    const auto j = nlohmann::json::parse(fileText(dir.path() / "release" / "summary.json"));
    EXPECT_GT(j["snap_back_releases"].get<long>(), 0);
    EXPECT_EQ(j["halvings"].get<long>(), 0);  // one halving per release before 2026-12-05: 2 here
    EXPECT_NEAR(j["energies_Nmm"]["dissipated"].get<double>(), 0.0239399, 1e-3 * 0.0239399);
  }
  {
    const Scene scene = readScene(io::parseYaml(replaced(weak, "  control:", "  snap_back: stop\n  control:"), "bar.yaml"));
    ASSERT_EQ(scene.solver.snapBack, SnapBackPolicy::Stop);
    const RunResult r = runScene(scene, quietRun(dir.path() / "stop"));
    EXPECT_FALSE(r.completed);
    ASSERT_TRUE(r.failure);
    EXPECT_EQ(r.failure->kind, FailureKind::SnapBack);
    EXPECT_EQ(r.failure->materialStatus, UpdateStatus::SnapBack);
    // The weak row is y = 490-500 mm: the point named lies in it.
    ASSERT_TRUE(r.failure->particle && r.failure->position);
    EXPECT_GT((*r.failure->position)[1], 489.0);
    EXPECT_LT((*r.failure->position)[1], 501.0);
    const auto j = nlohmann::json::parse(fileText(dir.path() / "stop" / "summary.json"));
    EXPECT_EQ(j["failure"]["kind"], "snap_back");
    EXPECT_EQ(j["failure"]["exit_status"], exitStatusOf(FailureKind::SnapBack));
    EXPECT_EQ(j["failure"]["particle"].get<std::size_t>(), *r.failure->particle);
    EXPECT_EQ(j["failure"]["material_status"], toString(UpdateStatus::SnapBack));
    EXPECT_EQ(j["status"], "failed");
    EXPECT_EQ(j["snap_back_releases"].get<long>(), 0);
    EXPECT_TRUE(std::filesystem::exists(dir.path() / "stop" / "checkpoint.bin"));  // the last converged state
  }
}

// An opening that cannot measure what it names is refused before anything runs: a point off the
// grid nodes and coefficients that are all 0 at their lines (Scene::validate), a node that no
// particle reaches (a margin node of the grid: its displacement would stay 0 and the control
// would compress the bar, peak 163 N against 58 N) when the run is set up, naming the term.
TEST(ImplicitScene, AnOpeningOffTheBodyOrOffTheNodesIsRefused) {
  const std::string bar = shippedBar();
  const auto err = [](const std::string& text) { return inputError([&] { readScene(io::parseYaml(text, "bar.yaml")); }); };
  {
    const auto e = err(replaced(bar, "{node: [0, 500], component: y", "{node: [5, 500], component: y"));
    expectContains(e.what(), "solver.control.indirect.opening[0].node");
    expectContains(e.what(), "(5, 500) mm is not a grid node (the nearest is (10, 500) mm)");
    EXPECT_EQ(e.line, 32);
  }
  {
    std::string zero = bar;
    for (std::size_t at; (at = zero.find("coefficient: 0.333333333333333333")) != std::string::npos || (at = zero.find("coefficient: -0.333333333333333333")) != std::string::npos;)
      zero.replace(at, zero.find('}', at) - at, "coefficient: 0");
    expectContains(err(zero).what(), "every coefficient is 0");
  }
  const Scene margin = readScene(io::parseYaml(replaced(bar, "{node: [0, 500], component: y", "{node: [-10, 500], component: y"), "bar.yaml"));
  ecm::test::TempDir dir;
  try {
    runScene(margin, quietRun(dir.path() / "margin"));
    ADD_FAILURE() << "an opening on a node no particle reaches was accepted";
  } catch (const std::invalid_argument& e) {
    expectContains(e.what(), "solver.control.indirect.opening[0]: the node (-10, 500) mm is reached by no particle");
  }
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "margin" / "history.csv"));  // refused before any output
}

// Quadratic B-splines are refused in implicit scenes with the reason: without a boundary
// modification a held edge makes the stresses oscillate next to it (the bar cracked at its held
// ends at 1.12 MPa, not in its weak row at 2.9 MPa).
TEST(ImplicitScene, BSplinesAreRefusedWithTheReason) {
  const auto e = inputError([&] {
    readScene(io::parseYaml(replaced(shippedBar(), "shape_function: linear", "shape_function: bspline2"), "bar.yaml"));
  });
  expectContains(e.what(), "bspline2 is not offered with implicit_static");
  EXPECT_EQ(e.line, 24);
}

// The bar pulled by its top under displacement control without stabilised steps: past its peak the
// closed form snaps back (docs/implicit.md), so the run must end there, and say why and what traces it.
TEST(ImplicitScene, WithoutStabilisedStepsDisplacementControlStopsAtTheStructuralSnapBackAndSaysSo) {
  const std::string bar = shippedBar();
  std::string text = bar.substr(0, bar.find("  control:")) + "  load_step: 0.01\n  max_halvings: 4\n  stabilization: 0\n" +
                     bar.substr(bar.find("end_time:"));
  text = replaced(text, "displacement: {y: {type: hold, value: 0}}", "displacement: {y: {type: linear_ramp, value: 0.12, time: 1}}");
  const Scene scene = readScene(io::parseYaml(text, "bar.yaml"));
  ASSERT_FALSE(scene.solver.implicit->indirect);
  ecm::test::TempDir dir;
  const RunResult r = runScene(scene, quietRun(dir.path() / "out"));
  EXPECT_FALSE(r.completed);
  // It got to the peak (2.9 MPa x 20 mm^2 = 58 N) before it failed.
  EXPECT_NEAR(r.peakLoad, 58.0, 0.01 * 58.0);
  ASSERT_TRUE(r.failure);
  EXPECT_TRUE(r.failure->kind == FailureKind::NewtonNotConverged || r.failure->kind == FailureKind::SingularTangent)
      << toString(r.failure->kind);
  EXPECT_TRUE(r.failure->likelyLimitPoint);
  EXPECT_EQ(nlohmann::json::parse(fileText(dir.path() / "out" / "summary.json"))["failure"]["likely_limit_point"], true);
}

// uGIMP with a free margin of grid nodes: the block's edge particles reach the margin nodes with
// weight and gradient exactly 0; those nodes carry nothing and are not unknowns (before, the
// first step's tangent was singular). The block (E 1000 MPa, nu 0, 10 x 10 mm, 1 mm thick) is
// pulled 0.01 mm: a uniform strain 1e-3 that uGIMP reproduces exactly, so the top's reaction is
// E A eps = 1000 x 10 x 1e-3 = 10 N to round-off.
TEST(ImplicitScene, UGimpWithAFreeMarginOfNodesRunsAndMatchesTheElasticClosedForm) {
  const std::string text = pulledBlockYaml("min-ugimp") + "solver: {scheme: implicit_static, shape_function: ugimp, load_step: 1}\n";
  const Scene scene = readScene(io::parseYaml(text, "min-ugimp.yaml"));
  ecm::test::TempDir dir;
  const RunResult r = runScene(scene, quietRun(dir.path() / "out"));
  ASSERT_TRUE(r.completed) << r.message();
  EXPECT_NEAR(r.peakLoad, 10.0, 1e-9 * 10.0);
}

}  // namespace
}  // namespace ecm::mpm::test
