// Gauges (mpm/scene/gauge.hpp): an extensometer across a uniformly strained block reads eps L in
// both solvers, a one-point gauge reads its material point's displacement, stop_when and the
// implicit solver's indirect control act on a gauge, and a gauge point outside the body is refused.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "../io/temp_dir.hpp"
#include "run_helpers.hpp"
#include "test_scenes.hpp"
#include "mpm/run.hpp"
#include "mpm/scene/scene_yaml.hpp"

namespace ecm::mpm::test {
namespace {

using namespace ecm::test;  // expectContains, inputError

// The pulled block (test_scenes.hpp: a uniform strain of 1e-3) with two gauges.
const std::string kBlock = pulledBlockYaml("gauge-block") + R"(gauges:
  - {name: extensometer, at: [2.4, 2.6], to: [2.6, 7.4], component: y}   # the seeds at (2.5, 2.5) and (2.5, 7.5)
  - {name: upper, at: [7.5, 7.5], component: y}
)";

// Implicit: the uniform strain is reached exactly (one load step, linear shape functions): the
// extensometer over 5 mm reads 1e-3 x 5 = 5e-3 mm and the upper point u_y = 1e-3 x 7.5 mm.
TEST(Gauge, AnExtensometerAcrossAUniformlyStrainedBlockReadsEpsTimesItsLengthImplicit) {
  const Scene scene = readScene(io::parseYaml(std::string(kBlock) + "solver: {scheme: implicit_static, load_step: 1}\n", "b.yaml"));
  ecm::test::TempDir dir;
  const RunResult r = runScene(scene, quietRun(dir.path() / "out"));
  ASSERT_TRUE(r.completed) << r.message();
  const auto row = lastRow(dir.path() / "out" / "history.csv");
  EXPECT_NEAR(row.at("extensometer_mm"), 5e-3, 1e-12);
  EXPECT_NEAR(row.at("upper_mm"), 7.5e-3, 1e-12);
  const auto j = nlohmann::json::parse(std::ifstream(dir.path() / "out" / "summary.json"));
  EXPECT_EQ(j["gauges"][0]["at_mm"][1].get<double>(), 2.5);  // the seeds it follows
  EXPECT_EQ(j["gauges"][0]["to_mm"][1].get<double>(), 7.5);
}

// Explicit: the grid nodes all follow an affine field v = s(t) G x (every shape function
// reproduces it), so the particles' displacements are the field's: u_y = e(t) y with
// e(t) = rate x integral of s, and the extensometer reads e(t) x 5 mm, the point e(t) x 7.5 mm.
TEST(Gauge, AnExtensometerInAnAffineFieldReadsEpsTimesItsLengthExplicit) {
  Scene s;
  s.grid = {Vec2(-10.0, -10.0), Vec2(10.0, 10.0), 3, 3};
  MaterialParams m{.name = "e", .model = ModelKind::LinearElastic, .elastic = {1000.0, 0.0, Hypothesis::PlaneStress},
                   .density = 1e-9};
  s.materials = {m};
  s.bodies = {{Shape::rectangle(Vec2(0.0, 0.0), Vec2(10.0, 10.0)), 0, false, Vec2::Zero()}};
  const double rate = 1.0;  // 1/s
  NodeCondition all;
  all.name = "all";
  all.box = {Vec2(-11.0, -11.0), Vec2(21.0, 21.0)};
  Mat2 g = Mat2::Zero();
  g(1, 1) = rate;
  all.field = AffineVelocity{g, Vec2::Zero(), TimeFunction::hold(1.0)};
  s.conditions = {all};
  s.gauges = {{"extensometer", Vec2(2.5, 2.5), Vec2(2.5, 7.5), 1}, {"upper", Vec2(7.5, 7.5), std::nullopt, 1}};
  s.endTime = 1e-3;
  s.validate();
  ecm::test::TempDir dir;
  const RunResult r = runScene(s, quietRun(dir.path() / "out"));
  ASSERT_TRUE(r.completed) << r.message();
  const auto row = lastRow(dir.path() / "out" / "history.csv");
  // The particles move with the field: y(t) = y0 exp(rate t) to the time step's order; the strain
  // from the displacement the run reports at its end time t is exp(rate t) - 1.
  const double t = row.at("time_s");
  const double e = std::expm1(rate * t);
  EXPECT_NEAR(row.at("extensometer_mm"), e * 5.0, 1e-3 * e * 5.0);
  EXPECT_NEAR(row.at("upper_mm"), e * 7.5, 1e-3 * e * 7.5);
}

// stop_when on a gauge: the run ends at the first row where the extensometer reaches 2e-3 mm
// (strain 4e-4, pseudo-time 0.4 with load steps of 0.1).
TEST(Gauge, StopWhenEndsTheRunWhereTheGaugeReachesItsValue) {
  const Scene scene = readScene(io::parseYaml(std::string(kBlock) + "solver: {scheme: implicit_static, load_step: 0.1}\n"
                                              "stop_when: {gauge: extensometer, reaches: 2e-3}\n", "b.yaml"));
  ecm::test::TempDir dir;
  const RunResult r = runScene(scene, quietRun(dir.path() / "out"));
  ASSERT_TRUE(r.completed) << r.message();
  EXPECT_TRUE(r.endedByStopWhen);
  const auto row = lastRow(dir.path() / "out" / "history.csv");
  EXPECT_GE(row.at("extensometer_mm"), 2e-3 * (1.0 - 1e-12));
  EXPECT_LT(row.at("extensometer_mm"), 2.5e-3);
}

// Indirect control on a gauge: the top follows the load factor while the extensometer grows
// 1e-3 mm per step to 4e-3 mm; the top then sits at 4e-3 x 10 / 5 = 8e-3 mm (uniform strain),
// to the strain's order (the particles move with each step while the top's nodes stay: the
// extensometer spans 5 (1 + eps) mm, eps < 1e-3).
TEST(Gauge, IndirectControlOnAGaugeDrivesItsReading) {
  std::string text = kBlock;
  text.replace(text.find("displacement: {y: {type: linear_ramp, value: 0.01, time: 1}}"),
               std::string("displacement: {y: {type: linear_ramp, value: 0.01, time: 1}}").size(), "displacement: {y: {type: hold, value: 0}}");
  const Scene scene = readScene(io::parseYaml(text + "solver: {scheme: implicit_static, control: {indirect: {driven: [top], "
                                                     "gauge: extensometer, step: 1e-3, until: 4e-3}}}\n", "b.yaml"));
  ecm::test::TempDir dir;
  const RunResult r = runScene(scene, quietRun(dir.path() / "out"));
  ASSERT_TRUE(r.completed) << r.message();
  const auto row = lastRow(dir.path() / "out" / "history.csv");
  EXPECT_NEAR(row.at("extensometer_mm"), 4e-3, 1e-9);
  EXPECT_NEAR(row.at("top_uy_mm"), 8e-3, 1e-3 * 8e-3);
}

TEST(Gauge, BadGaugesAreRefused) {
  const auto err = [](const std::string& tail) {
    return inputError([&] { readScene(io::parseYaml(std::string(kBlock) + tail, "b.yaml")); });
  };
  expectContains(err("stop_when: {gauge: nothing, reaches: 1}\nsolver: {scheme: implicit_static, load_step: 1}\n").what(), "no gauge is named 'nothing'");
  std::string twice = kBlock;
  twice.replace(twice.find("name: upper"), 11, "name: extensometer");
  expectContains(inputError([&] { readScene(io::parseYaml(twice, "b.yaml")); }).what(), "'extensometer' is defined twice");
  // A point outside the body: refused when the run is set up, naming the gauge.
  std::string outside = kBlock;
  outside.replace(outside.find("at: [7.5, 7.5]"), 14, "at: [17.5, 7.5]");
  const Scene scene = readScene(io::parseYaml(outside + "solver: {scheme: implicit_static, load_step: 1}\n", "b.yaml"));
  ecm::test::TempDir dir;
  try {
    runScene(scene, quietRun(dir.path() / "out"));
    ADD_FAILURE() << "a gauge outside the body was accepted";
  } catch (const std::invalid_argument& e) {
    expectContains(e.what(), "gauges[1].at: (17.5, 7.5) mm is outside the body (no particle within one particle spacing");
  }
}

}  // namespace
}  // namespace ecm::mpm::test
