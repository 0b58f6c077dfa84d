// The explicit run's energy check (mpm/explicit/energy_check.hpp, docs/model.md "The damping's
// work"): the damping's work may not leave [-1, 1] times the energy put into the run.
#include <gtest/gtest.h>

#include <filesystem>

#include "../io/temp_dir.hpp"
#include "io/csv_reader.hpp"
#include "mpm/explicit/energy_check.hpp"
#include "mpm/run.hpp"
#include "mpm/scene/scene_yaml.hpp"
#include "run_helpers.hpp"

namespace ecm::mpm {
namespace {

TEST(EnergyCheck, TheDampingMayTakeWhatWasPutInAndPutNothingIn) {
  RunTotals e{};
  e.externalWork = 10.0;
  e.damping = 9.0;
  EXPECT_FALSE(dampingOutrunsInput(e, 0.0));
  e.damping = 10.5;
  EXPECT_TRUE(dampingOutrunsInput(e, 0.0));
  EXPECT_FALSE(dampingOutrunsInput(e, 1.0));  // the particles' initial energy counts as put in
  e.damping = -10.5;                          // energy made by the damping
  EXPECT_TRUE(dampingOutrunsInput(e, 0.0));
  e.externalWork = 0.0;
  e.damping = 0.0;
  EXPECT_FALSE(dampingOutrunsInput(e, 0.0));  // nothing in, nothing taken: a run at rest
}

// An explicit step past its stability limit (the coarse L-panel at the largest CFL number, 1.0,
// with Cundall damping and a row every step): the energies run away within a few steps. The run
// stops loudly at the first row where the damping's work is beyond what was put in, before a
// particle leaves the grid (step 22 without the check), and keeps that row.
TEST(EnergyCheck, AnUnstableStepStopsTheRunAtItsRow) {
  ecm::test::TempDir tmp;
  Scene s = loadSceneFile(std::filesystem::path(ECM_SOURCE_DIR) / "data/validation/lpanel-coarse.yaml");
  s.solver.explicitScheme.cfl = 1.0;
  s.outputInterval = 1e-9;  // every step
  RunOptions o = test::quietRun(tmp.path() / "out");
  const RunResult r = runScene(s, o);
  ASSERT_FALSE(r.completed);
  ASSERT_TRUE(r.failure);
  EXPECT_EQ(r.failure->kind, FailureKind::DampingWork) << r.message();
  EXPECT_EQ(r.failure->step, r.steps);
  EXPECT_LT(r.steps, 22);
  const io::CsvTable h = io::readCsv(o.outputDir / "history.csv");
  EXPECT_EQ(static_cast<long>(h.rows.back()[1]), r.steps);  // the failing step's row is kept
}

}  // namespace
}  // namespace ecm::mpm
