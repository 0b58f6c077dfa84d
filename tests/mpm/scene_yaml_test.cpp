// The YAML scene reader: the shipped scenes load; unknown keys, missing keys and bad values are
// refused with FILE:LINE: reason.
#include <gtest/gtest.h>

#include "../io/temp_dir.hpp"
#include "mpm/scene/memory_estimate.hpp"
#include "mpm/scene/presets.hpp"
#include "mpm/scene/scene_yaml.hpp"

namespace ecm::mpm::test {
namespace {

using namespace ecm::test;  // expectContains, inputError, TempDir

const std::string kScene = R"(name: t
grid: {origin: [0, 0], cell_size: [10, 10], cells: [10, 12]}
materials:
  - {name: e, model: linear_elastic, hypothesis: plane_stress, youngs_modulus: 1000, poisson_ratio: 0.2, density: 1e-9}
bodies:
  - {rectangle: {min: [0, 0], max: [100, 100]}, material: e}
end_time: 1e-3
conditions:
  - {name: base, box: {min: [0, 0], max: [100, 0]}, fixed: [x, y]}
)";

TEST(SceneYaml, TheSnapBackDefaultIsReleaseInEveryReader) {
  // docs/inputs.md: `snap_back: release` is the default; it has one home
  // (material/snap_back_policy.hpp), which the scene reader and the settings' defaults read.
  static_assert(kDefaultSnapBack == SnapBackPolicy::Release);
  EXPECT_EQ(SolverSettings{}.snapBack, kDefaultSnapBack);
  EXPECT_EQ(readScene(io::parseYaml(kScene, "t.yaml")).solver.snapBack, kDefaultSnapBack);
  EXPECT_EQ(readScene(io::parseYaml(kScene + "solver: {snap_back: stop}\n", "t.yaml")).solver.snapBack, SnapBackPolicy::Stop);
  EXPECT_STREQ(toString(kDefaultSnapBack), "release");
  EXPECT_EQ(snapBackPolicyOf("stop"), SnapBackPolicy::Stop);
  EXPECT_EQ(snapBackPolicyOf("jump"), std::nullopt);
}

// docs/inputs.md: crack paths are tracked unless a scene says `crack_path: free` (the paper's rule),
// as the paper's scenes do; the validation scenes (the beam, the DEN rig, the L-panel) are tracked.
TEST(SceneYaml, CrackPathsAreTrackedUnlessASceneSaysFree) {
  EXPECT_EQ(SolverSettings{}.crackPath, CrackPathRule::Tracked);
  EXPECT_EQ(readScene(io::parseYaml(kScene, "t.yaml")).solver.crackPath, CrackPathRule::Tracked);
  EXPECT_EQ(readScene(io::parseYaml(kScene + "solver: {crack_path: free}\n", "t.yaml")).solver.crackPath,
            CrackPathRule::Free);
  const auto data = std::filesystem::path(ECM_SOURCE_DIR) / "data";
  for (const char* free : {"den/den-4b-coarse.yaml", "rve/rve-coarse.yaml", "mpm/bar-snapback-explicit.yaml"})
    EXPECT_EQ(loadSceneFile(data / free).solver.crackPath, CrackPathRule::Free) << free;
  for (const auto& entry : std::filesystem::directory_iterator(data / "validation"))
    EXPECT_EQ(loadSceneFile(entry.path()).solver.crackPath, CrackPathRule::Tracked) << entry.path();
}

TEST(SceneYaml, ShippedSecondBandScenesDifferOnlyInTheMaterialOption) {
  for (const std::string mesh : {"coarse", "medium", "fine", "coarse-implicit", "medium-implicit"}) {
    const auto dir = std::filesystem::path(ECM_SOURCE_DIR) / "data" / "den";
    const std::string scheme = mesh.ends_with("-implicit") ? "-implicit" : "";
    const std::string size = mesh.substr(0, mesh.size() - scheme.size());
    const Scene off = loadSceneFile(dir / ("den-4b-" + mesh + ".yaml"));
    const Scene on = loadSceneFile(dir / ("den-4b-" + size + "-second-band" + scheme + ".yaml"));
    EXPECT_EQ(on.solver.implicit.has_value(), off.solver.implicit.has_value()) << mesh;
    ASSERT_EQ(on.materials.size(), 1u);
    EXPECT_EQ(on.materials[0].secondBand, SecondBandOption::Orthogonal) << mesh;
    EXPECT_EQ(off.materials[0].secondBand, SecondBandOption::Off) << mesh;
    EXPECT_EQ(on.grid.cellSize, off.grid.cellSize);
    EXPECT_EQ(on.endTime, off.endTime);
    EXPECT_EQ(on.conditions.size(), off.conditions.size());
  }
}

// The fine rate-free DEN is the medium one on the fine explicit scenes' grid: the same solver
// settings, control, conditions, loads and stop.
TEST(SceneYaml, ShippedFineImplicitSceneIsTheMediumOneOnTheFineGrid) {
  const auto dir = std::filesystem::path(ECM_SOURCE_DIR) / "data" / "den";
  const Scene fine = loadSceneFile(dir / "den-4b-fine-second-band-implicit.yaml");
  const Scene medium = loadSceneFile(dir / "den-4b-medium-second-band-implicit.yaml");
  const Scene explicitFine = loadSceneFile(dir / "den-4b-fine-second-band.yaml");
  EXPECT_EQ(fine.grid.origin, explicitFine.grid.origin);
  EXPECT_EQ(fine.grid.cellSize, explicitFine.grid.cellSize);
  EXPECT_EQ(fine.grid.cellsX, explicitFine.grid.cellsX);
  EXPECT_EQ(fine.grid.cellsY, explicitFine.grid.cellsY);
  EXPECT_EQ(fine.particlesPerCell, medium.particlesPerCell);
  ASSERT_TRUE(fine.solver.implicit.has_value());
  ASSERT_TRUE(medium.solver.implicit.has_value());
  const ImplicitSettings& a = *fine.solver.implicit;
  const ImplicitSettings& b = *medium.solver.implicit;
  EXPECT_EQ(a.tolerance, b.tolerance);
  EXPECT_EQ(a.acceptTolerance, b.acceptTolerance);
  EXPECT_EQ(a.onsetOvershoot, b.onsetOvershoot);
  EXPECT_EQ(a.loadStep, b.loadStep);
  ASSERT_TRUE(a.indirect.has_value());
  ASSERT_TRUE(b.indirect.has_value());
  EXPECT_EQ(a.indirect->step, b.indirect->step);
  EXPECT_EQ(a.indirect->until, b.indirect->until);
  EXPECT_EQ(a.indirect->terms.size(), b.indirect->terms.size());
  EXPECT_EQ(fine.materials[0].secondBand, SecondBandOption::Orthogonal);
  EXPECT_EQ(fine.conditions.size(), medium.conditions.size());
  EXPECT_EQ(fine.loads.size(), medium.loads.size());
  EXPECT_EQ(fine.endTime, medium.endTime);
  EXPECT_EQ(fine.stopWhen.has_value(), medium.stopWhen.has_value());
}

// The validation's fine rate-free scenes (DEN rig, L-panel) are the medium ones on the fine explicit
// scenes' grid, with the fine scenes' supports; every DEN and L-panel validation scene carries the
// second band (docs/validation.md: a curved crack locks a single band).
TEST(SceneYaml, ValidationFineImplicitScenesAreTheMediumOnesOnTheFineGrid) {
  const auto dir = std::filesystem::path(ECM_SOURCE_DIR) / "data" / "validation";
  for (const std::string test : {"den-4b-rig", "lpanel"}) {
    const Scene fine = loadSceneFile(dir / (test + "-fine-implicit.yaml"));
    const Scene medium = loadSceneFile(dir / (test + "-medium-implicit.yaml"));
    const Scene explicitFine = loadSceneFile(dir / (test + "-fine.yaml"));
    EXPECT_EQ(fine.grid.origin, explicitFine.grid.origin) << test;
    EXPECT_EQ(fine.grid.cellSize, explicitFine.grid.cellSize) << test;
    EXPECT_EQ(fine.grid.cellsX, explicitFine.grid.cellsX) << test;
    EXPECT_EQ(fine.grid.cellsY, explicitFine.grid.cellsY) << test;
    ASSERT_EQ(fine.conditions.size(), explicitFine.conditions.size()) << test;
    for (std::size_t k = 0; k < fine.conditions.size(); ++k) {
      EXPECT_EQ(fine.conditions[k].box.min, explicitFine.conditions[k].box.min) << test << " " << k;
      EXPECT_EQ(fine.conditions[k].box.max, explicitFine.conditions[k].box.max) << test << " " << k;
    }
    ASSERT_TRUE(fine.solver.implicit.has_value() && medium.solver.implicit.has_value()) << test;
    EXPECT_EQ(fine.solver.implicit->tolerance, medium.solver.implicit->tolerance) << test;
    EXPECT_EQ(fine.solver.implicit->loadStep, medium.solver.implicit->loadStep) << test;
    EXPECT_EQ(fine.solver.implicit->indirect.has_value(), medium.solver.implicit->indirect.has_value()) << test;
    EXPECT_EQ(fine.endTime, medium.endTime) << test;
    ASSERT_EQ(fine.platens.size(), explicitFine.platens.size()) << test;
    for (std::size_t k = 0; k < fine.platens.size(); ++k) {
      ASSERT_EQ(fine.platens[k].boxes.size(), explicitFine.platens[k].boxes.size()) << test;
      for (std::size_t b = 0; b < fine.platens[k].boxes.size(); ++b) {
        EXPECT_EQ(fine.platens[k].boxes[b].min, explicitFine.platens[k].boxes[b].min) << test << " platen " << k;
        EXPECT_EQ(fine.platens[k].boxes[b].max, explicitFine.platens[k].boxes[b].max) << test << " platen " << k;
      }
    }
    for (const char* mesh : {"coarse", "coarse-implicit", "medium", "medium-implicit", "fine", "fine-implicit"}) {
      const Scene scene = loadSceneFile(dir / (test + "-" + mesh + ".yaml"));
      ASSERT_EQ(scene.materials.size(), 1u);
      EXPECT_EQ(scene.materials[0].secondBand, SecondBandOption::Orthogonal) << test << "-" << mesh;
    }
  }
}

TEST(SceneYaml, ShippedScenesLoad) {
  // The values the files hold (the reader has validated them already).
  const Scene bar = loadSceneFile(std::filesystem::path(ECM_SOURCE_DIR) / "data" / "mpm" / "elastic-bar.yaml");
  EXPECT_EQ(bar.grid.cellsX, 68);
  EXPECT_EQ(bar.grid.cellsY, 3);
  EXPECT_EQ(bar.grid.cellSize, Vec2(1.5625, 1.5625));
  EXPECT_EQ(bar.endTime, 2.2e-4);
  EXPECT_EQ(bar.materials[0].model, ModelKind::LinearElastic);
  const Scene block = loadSceneFile(std::filesystem::path(ECM_SOURCE_DIR) / "data" / "mpm" / "tension-block.yaml");
  EXPECT_EQ(block.materials[0].model, ModelKind::Enriched);
  EXPECT_EQ(block.bodies.size(), 3u);
  EXPECT_TRUE(block.bodies[1].subtract);
  EXPECT_EQ(block.conditions[1].component[1].kind, Prescribed::Displacement);
  EXPECT_DOUBLE_EQ(block.conditions[1].component[1].history(1.0), 0.04);
  EXPECT_EQ(block.endTime, 2e-3);
  EXPECT_EQ(block.grid.cellSize, Vec2(5.0, 5.0));
}

TEST(SceneYaml, ReadsEveryPart) {
  const std::string text = kScene + R"(solver: {scheme: musl, shape_function: ugimp, flip: 0.9, cfl: 0.5, effective_size: oriented,
         local_damping: 0.1, viscous_damping: 5, gravity: [0, -9810], substep_levels: 3}
output_interval: 1e-4
loads:
  - {name: pull, box: {min: [0, 95], max: [100, 100]}, on: nodes, force: [0, 10],
     history: {type: table, points: [[0, 0], [1e-3, 1]]}}
)";
  const Scene s = readScene(io::parseYaml(text, "scene.yaml"));
  EXPECT_EQ(s.solver.explicitScheme.scheme, UpdateScheme::MUSL);
  EXPECT_EQ(s.solver.shapeFunction, ShapeFunction::UGimp);
  EXPECT_EQ(s.solver.effectiveSize, EffectiveSizeRule::Oriented);
  EXPECT_DOUBLE_EQ(s.solver.gravity[1], -9810.0);
  EXPECT_EQ(s.loads[0].target, LoadTarget::Nodes);
  EXPECT_DOUBLE_EQ(s.loads[0].history(5e-4), 0.5);
  EXPECT_EQ(s.conditions[0].component[0].kind, Prescribed::Fixed);
}

TEST(SceneYaml, ErrorsNameFileAndLine) {
  auto err = [](const std::string& text) { return inputError([&] { readScene(io::parseYaml(text, "scene.yaml")); }); };
  {
    // Cells of 1e-5 mm give H = 1e-5 mm, below h (1 + 1e-6) for h = 0.05 mm (docs/model.md).
    std::string t = kScene;
    t.replace(t.find("cell_size: [10, 10]"), 19, "cell_size: [1e-5, 1e-5]");
    t.replace(t.find("max: [100, 100]"), 15, "max: [1e-4, 1e-4]");
    t.replace(t.find("max: [100, 0]"), 13, "max: [1e-4, 0]");
    t.replace(t.find("model: linear_elastic,"), 22,
              "model: enriched, tensile_strength: 3, softening_modulus: 8, softening_exponent: 0.1, band_width: 0.05,");
    const auto e = err(t);
    EXPECT_EQ(e.line, 4);
    expectContains(e.what(), "0.05000005 mm");
  }
  {
    // second_band: orthogonal needs H >= 2 h (1 + 1e-6) = 0.1000001 mm: cells of 0.1 mm are refused.
    std::string t = kScene;
    t.replace(t.find("cell_size: [10, 10]"), 19, "cell_size: [0.1, 0.1]");
    t.replace(t.find("max: [100, 100]"), 15, "max: [1, 1]");
    t.replace(t.find("max: [100, 0]"), 13, "max: [1, 0]");
    t.replace(t.find("model: linear_elastic,"), 22,
              "model: enriched, tensile_strength: 3, softening_modulus: 8, softening_exponent: 0.1, band_width: 0.05, "
              "second_band: orthogonal,");
    const auto e = err(t);
    EXPECT_EQ(e.line, 4);
    expectContains(e.what(), "0.1000001 mm");
    expectContains(e.what(), "room for two bands");
  }
  {
    const auto e = err(kScene + "bogus: 1\n");
    EXPECT_EQ(e.line, 10);
    expectContains(e.what(), "scene.yaml:10:");
    expectContains(e.what(), "bogus");
  }
  {
    std::string t = kScene;
    t.replace(t.find("end_time: 1e-3\n"), 15, "");
    expectContains(err(t).what(), "end_time");
  }
  {
    const auto e = err(kScene + "particle_snapshots: [5e-4, 2e-4]\n");
    EXPECT_EQ(e.line, 10);
    expectContains(e.what(), "times must increase");
    expectContains(err(kScene + "particle_snapshots: [2e-3]\n").what(), "after end_time");
    expectContains(err(kScene + "particle_snapshots: [-1e-4]\n").what(), "particle_snapshots");
  }
  {
    const auto e = err(kScene + "solver: {cfl: 1.5}\n");
    EXPECT_EQ(e.line, 10);
    expectContains(e.what(), "cfl");
  }
  {
    std::string t = kScene;
    t.replace(t.find("material: e}"), 12, "material: x}");
    const auto e = err(t);
    EXPECT_EQ(e.line, 6);  // the body's line
    expectContains(e.what(), "unknown material 'x'");
  }
  {
    std::string t = kScene;
    t.replace(t.find("max: [100, 0]}"), 14, "max: [100, 0]}, displacement: {z: {type: hold, value: 1}}");
    expectContains(err(t).what(), "'z'");  // unknown key in the displacement map
  }
  {
    const auto e = err(kScene + "  - {name: far, box: {min: [500, 500], max: [600, 600]}, fixed: [x]}\n");
    EXPECT_EQ(e.line, 10);
    expectContains(e.what(), "contains no grid node");
  }
  {
    const auto e = err(kScene + "loads:\n  - {name: l, box: {min: [0, 0], max: [1, 1]}, force: [0, 1],\n     history: {type: linear_ramp, value: 1, time: -1}}\n");
    EXPECT_EQ(e.line, 12);
    expectContains(e.what(), "time");
  }
  {
    const auto e = err(kScene + "bodies2: []\n");
    expectContains(e.what(), "bodies2");
  }
}

TEST(SceneYaml, CheckpointKeysAreReadAndChecked) {
  const Scene none = readScene(io::parseYaml(kScene, "scene.yaml"));
  EXPECT_EQ(none.checkpoint.everySteps, 0);
  EXPECT_EQ(none.checkpoint.everyMinutes, 0.0);
  const Scene both = readScene(io::parseYaml(kScene + "checkpoint: {every_steps: 5000, every_minutes: 2.5}\n", "scene.yaml"));
  EXPECT_EQ(both.checkpoint.everySteps, 5000);
  EXPECT_EQ(both.checkpoint.everyMinutes, 2.5);
  const Scene steps = readScene(io::parseYaml(kScene + "checkpoint:\n  every_steps: 10\n", "scene.yaml"));
  EXPECT_EQ(steps.checkpoint.everySteps, 10);
  EXPECT_EQ(steps.checkpoint.everyMinutes, 0.0);

  auto err = [](const std::string& tail) {
    return inputError([&] { readScene(io::parseYaml(kScene + tail, "scene.yaml")); });
  };
  for (const auto& [tail, reason] : std::vector<std::pair<std::string, std::string>>{
           {"checkpoint: {every_steps: 0}\n", "every_steps"},          // out of range: >= 1
           {"checkpoint: {every_steps: 2.5}\n", "every_steps"},        // not an integer
           {"checkpoint: {every_steps: often}\n", "every_steps"},      // not a number
           {"checkpoint: {every_minutes: 0}\n", "every_minutes"},      // > 0
           {"checkpoint: {every_minutes: -1}\n", "every_minutes"},
           {"checkpoint: {every_hours: 1}\n", "unknown key 'every_hours'"},
           {"checkpoint: {every_steps: 10, at_exit: true}\n", "unknown key 'at_exit'"},
           {"checkpoint: {}\n", "every_steps: N and/or every_minutes: M"},
           {"checkpoint: 100\n", "checkpoint"}}) {
    const io::InputError e = err(tail);
    EXPECT_EQ(e.line, 10) << tail;
    expectContains(e.what(), "scene.yaml:10:");
    expectContains(e.what(), reason);
  }
}

// Values are checked by Scene::validate alone; the reader reports them at the line of the key
// they name, however deep: the line numbers below are those of kScene plus the tail.
TEST(SceneYaml, ValueErrorsFromValidateAreReportedAtTheirKeysLine) {
  auto err = [](const std::string& tail) { return inputError([&] { readScene(io::parseYaml(kScene + tail, "scene.yaml")); }); };
  const std::string twoConditions = "  - name: top\n"       // line 10
                                    "    box: {min: [0, 200], max: [100, 200]}\n"  // line 11: above the grid
                                    "    fixed: [y]\n";
  io::InputError e = err(twoConditions);
  EXPECT_EQ(e.line, 11);
  expectContains(e.what(), "key 'conditions[1].box': contains no grid node");
  e = err("solver:\n  flip: 0.5\n  cfl: 1.5\n");  // cfl on line 12
  EXPECT_EQ(e.line, 12);
  expectContains(e.what(), "key 'solver.cfl': 1.5 is outside the allowed range (0, 1]");
  e = err("loads:\n  - name: pull\n    box: {min: [0, 90], max: [100, 100]}\n    force: [0, 1]\n"
          "    history: {type: linear_ramp, value: 1, time: -1}\n");  // line 14
  EXPECT_EQ(e.line, 14);
  expectContains(e.what(), "key 'loads[0].history'");
}

// A scene the machine cannot hold is refused before anything is allocated, at its grid's line,
// with the estimate and the memory available: 40000 x 40000 cells of 2 x 2 particles is 6.4e9
// particles at most and 1.6e9 nodes, about 1.5 TiB.
TEST(SceneYaml, ASceneTooLargeForTheMachineIsRefusedAtItsGrid) {
  std::string big = kScene;
  big.replace(big.find("cells: [10, 12]"), 15, "cells: [40000, 40000]");
  big.replace(big.find("max: [100, 100]"), 15, "max: [400000, 400000]");
  const Scene asRead = [&] {  // the same scene's estimate, without the check
    Scene s;
    s.grid = {Vec2::Zero(), Vec2(10.0, 10.0), 40000, 40000};
    s.bodies = {{Shape::rectangle(Vec2::Zero(), Vec2(400000.0, 400000.0)), 0, false, Vec2::Zero()}};
    s.particlesPerCell = 2;
    return s;
  }();
  const MemoryEstimate e = estimateMemory(asRead);
  EXPECT_GT(e.particles, 6'000'000'000u);
  EXPECT_GT(e.bytes, 1'000'000'000'000u);
  const std::optional<std::size_t> available = availableMemory();
  if (!available) GTEST_SKIP() << "this machine does not say how much memory it has";
  ASSERT_LT(*available, e.bytes) << "a machine with more than 1.5 TiB free holds this scene";
  const io::InputError err = inputError([&] { readScene(io::parseYaml(big, "big.yaml")); });
  EXPECT_EQ(err.line, 2);
  expectContains(err.what(), "big.yaml:2");
  expectContains(err.what(), "key 'grid'");
  expectContains(err.what(), "GiB available");
}

// stop_when names one of the scene's conditions, a fraction in (0, 1) and a time before end_time.
TEST(SceneYaml, StopWhenKeysAreReadAndChecked) {
  EXPECT_FALSE(readScene(io::parseYaml(kScene, "scene.yaml")).stopWhen);
  const std::string scene = kScene + "output_interval: 1e-5\n";  // line 10: stop_when is line 11
  const Scene s = readScene(io::parseYaml(scene + "stop_when: {condition: base, load_below: 0.1, after_time: 5e-4}\n", "scene.yaml"));
  ASSERT_TRUE(s.stopWhen);
  EXPECT_EQ(s.stopWhen->condition, "base");
  EXPECT_EQ(s.stopWhen->loadBelow, 0.1);
  EXPECT_EQ(s.stopWhen->afterTime, 5e-4);
  EXPECT_EQ(readScene(io::parseYaml(scene + "stop_when: {condition: base, load_below: 0.5}\n", "scene.yaml")).stopWhen->afterTime,
            0.0);
  for (const auto& [tail, reason] : std::vector<std::pair<std::string, std::string>>{
           {"stop_when: {condition: top, load_below: 0.1}\n", "no condition is named 'top'"},
           {"stop_when: {condition: base, load_below: 1.0}\n", "load_below"},   // a fraction in (0, 1)
           {"stop_when: {condition: base, load_below: 0}\n", "load_below"},
           {"stop_when: {condition: base, load_below: low}\n", "load_below"},  // not a number
           {"stop_when: {condition: base}\n", "load_below"},                    // missing
           {"stop_when: {load_below: 0.1}\n", "condition"},
           {"stop_when: {condition: base, load_below: 0.1, after_time: -1}\n", "after_time"},
           {"stop_when: {condition: base, load_below: 0.1, after_time: 2e-3}\n", "not before end_time"},
           {"stop_when: {condition: base, load_below: 0.1, every: 2}\n", "unknown key 'every'"}}) {
    const io::InputError e = inputError([&] { readScene(io::parseYaml(scene + tail, "scene.yaml")); });
    EXPECT_EQ(e.line, 11) << tail;
    expectContains(e.what(), "scene.yaml:11:");
    expectContains(e.what(), reason);
  }
  const io::InputError e = inputError(
      [&] { readScene(io::parseYaml(kScene + "stop_when: {condition: base, load_below: 0.1}\n", "scene.yaml")); });
  expectContains(e.what(), "scene.yaml:10:");
  expectContains(e.what(), "needs output_interval > 0");
}

}  // namespace
}  // namespace ecm::mpm::test

namespace ecm::mpm::test {
namespace {

// A preset sets particles per cell, shape function, scheme and CFL (mpm/scene/presets.hpp); the scene
// may not set them as well, and an unknown preset is refused with the allowed names.
TEST(SceneYaml, PresetSetsItsKnobsAndOwnsThem) {
  const std::string base = R"(name: t
grid: {origin: [0, 0], cell_size: [10, 10], cells: [10, 12]}
materials:
  - {name: e, model: linear_elastic, hypothesis: plane_stress, youngs_modulus: 1000, poisson_ratio: 0.2, density: 1e-9}
bodies:
  - {rectangle: {min: [0, 0], max: [100, 100]}, material: e}
end_time: 1e-3
)";
  for (const Preset& p : presets()) {
    const Scene s = readScene(io::parseYaml(base + "preset: " + std::string(p.name) + "\nsolver: {flip: 0.9}\n", "scene.yaml"));
    EXPECT_EQ(s.preset, p.name);
    EXPECT_EQ(s.particlesPerCell, p.particlesPerCell);
    EXPECT_EQ(s.solver.explicitScheme.cfl, p.cfl);
    EXPECT_EQ(s.solver.shapeFunction, p.shapeFunction);
    EXPECT_EQ(s.solver.explicitScheme.scheme, p.scheme);
    EXPECT_EQ(s.solver.explicitScheme.flip, 0.9);  // knobs outside the preset stay the scene's
  }
  // The presets order speed against accuracy: particles per cell and time steps never fewer.
  const Preset& fast = *findPreset("fast");
  const Preset& accurate = *findPreset("accurate");
  EXPECT_LE(fast.particlesPerCell, accurate.particlesPerCell);
  EXPECT_GE(fast.cfl, accurate.cfl);
  EXPECT_EQ(readScene(io::parseYaml(base, "scene.yaml")).preset, "");

  auto err = [&](const std::string& tail) { return inputError([&] { readScene(io::parseYaml(base + tail, "scene.yaml")); }); };
  {
    const auto e = err("preset: fast\nparticles_per_cell: 3\n");
    EXPECT_EQ(e.line, 9);
    expectContains(e.what(), "set by preset 'fast'");
  }
  {
    const auto e = err("preset: accurate\nsolver:\n  flip: 0.99\n  cfl: 0.4\n");
    EXPECT_EQ(e.line, 11);
    expectContains(e.what(), "cfl");
  }
  expectContains(err("preset: turbo\n").what(), "fast");
}

}  // namespace
}  // namespace ecm::mpm::test
