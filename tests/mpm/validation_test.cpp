// The validation scenes (data/validation/, docs/validation.md) to their peaks, coarse meshes: the
// rigs' statics and the peaks measured in docs/validation.md. (The whole runs, against the tests'
// curves, are scripts/validate.sh, labelled slow.)
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <sstream>

#include "../io/temp_dir.hpp"
#include "run_helpers.hpp"
#include "mpm/run.hpp"
#include "mpm/scene/scene_yaml.hpp"

namespace ecm::mpm::test {
namespace {

const std::map<std::string, double>& peakRow(const std::vector<std::map<std::string, double>>& r, const std::string& column) {
  return *std::max_element(r.begin(), r.end(), [&](const auto& a, const auto& b) { return a.at(column) < b.at(column); });
}

// The DEN with its rig, explicit, to past its peak (t = 2.6 ms; the peak is at 1.82 ms).
// Statics of the rig at the peak (a quasi-static run: the inertia forces are a small part): the
// lower frame's reactions balance the upper frame's force on the specimen in x (P_s = 10 kN,
// force-driven) and in y (P) to 1 % of P; the upper frame stays level. The peak: 18.26 kN
// (docs/validation.md, tracked crack paths and the second band, measured 2026-12-07), asserted to 0.5 %.
TEST(Validation, TheDenRigCoarseToItsPeak) {
  Scene scene = loadSceneFile(std::filesystem::path(ECM_SOURCE_DIR) / "data/validation/den-4b-rig-coarse.yaml");
  scene.endTime = 0.0026;
  scene.stopWhen.reset();
  ecm::test::TempDir dir;
  const RunResult r = runScene(scene, quietRun(dir.path() / "out"));
  ASSERT_TRUE(r.completed) << r.message();
  const auto history = historyRows(dir.path() / "out" / "history.csv");
  const auto& peak = peakRow(history, "upper-frame_Fy_N");
  const double p = peak.at("upper-frame_Fy_N");
  EXPECT_NEAR(p, 18260.0, 0.005 * 18260.0);
  EXPECT_NEAR(peak.at("upper-frame_Fx_N"), 10000.0, 1e-9 * 10000.0);  // force-driven: P_s to round-off (a Debug build sums it otherwise)
  EXPECT_EQ(peak.at("upper-frame_rotation_rad"), 0.0);
  EXPECT_NEAR(peak.at("upper-frame_Fx_N") + peak.at("bottom_rx_N") + peak.at("right-lower_rx_N"), 0.0, 0.01 * p);
  EXPECT_NEAR(peak.at("upper-frame_Fy_N") + peak.at("bottom_ry_N") + peak.at("right-lower_ry_N"), 0.0, 0.01 * p);
  EXPECT_GT(peak.at("delta-left_mm"), 0.0);  // the gauges open with the tension
}

// Winkler's L-panel, explicit, coarse mesh, to u = 0.2 mm: the peak, 6.42 kN at u = 0.14 mm
// (docs/validation.md, tracked crack paths and the second band, measured 2026-12-07), asserted to 1 %.
// Statics: the explicit panel rings (single rows of the rising branch are out of balance by up to
// 15 % of F), so the clamp's reaction is held to the load plate's force over the rising branch's
// rows from u = 0.05 mm to the peak: their sums balance to 2.5 % (measured 1.9 %, the local
// damping's force on the moving arm); at the peak row to 4 % (measured 3.1 %). The hinged plate
// carries no moment.
TEST(Validation, TheLPanelCoarseToItsPeak) {
  Scene scene = loadSceneFile(std::filesystem::path(ECM_SOURCE_DIR) / "data/validation/lpanel-coarse.yaml");
  scene.endTime = 0.0125;
  ecm::test::TempDir dir;
  const RunResult r = runScene(scene, quietRun(dir.path() / "out"));
  ASSERT_TRUE(r.completed) << r.message();
  const auto history = historyRows(dir.path() / "out" / "history.csv");
  const auto& peak = peakRow(history, "load-plate_Fy_N");
  const double f = peak.at("load-plate_Fy_N");
  EXPECT_NEAR(f, 6420.0, 0.01 * 6420.0);
  EXPECT_NEAR(peak.at("load-plate_uy_mm"), 0.14, 0.02);
  EXPECT_NEAR(f + peak.at("clamp_ry_N"), 0.0, 0.04 * f);
  double load = 0.0, imbalance = 0.0;
  for (const auto& row : history) {
    if (row.at("load-plate_uy_mm") < 0.05 || row.at("load-plate_uy_mm") > peak.at("load-plate_uy_mm")) continue;
    load += row.at("load-plate_Fy_N");
    imbalance += row.at("load-plate_Fy_N") + row.at("clamp_ry_N");
  }
  EXPECT_GT(load, 10.0 * f);  // at least ten rows
  EXPECT_NEAR(imbalance, 0.0, 0.025 * load);
  EXPECT_EQ(peak.at("load-plate_M_Nmm"), 0.0);
}

}  // namespace
}  // namespace ecm::mpm::test
