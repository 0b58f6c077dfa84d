// stop_when: a softening run ends at the first output row where the watched reaction has fallen
// below the given fraction of its peak (mpm/scene/stop_when.hpp); the watch survives a restart.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "../io/temp_dir.hpp"
#include "io/csv_reader.hpp"
#include "mpm/run.hpp"
#include "test_scenes.hpp"
#include "run_helpers.hpp"

namespace ecm::mpm::test {
namespace {

namespace fs = std::filesystem;
using namespace ecm::test;  // readFile, TempDir

TEST(StopWatch, FiresBelowTheFractionOfThePeakOnlyFromAfterTime) {
  const StopWhen when{"top", 0.1, 1.0, {}, 0.0};
  StopWatch w;
  EXPECT_FALSE(w.observe(when, 0.0, 0.0));    // no peak yet: 0 < 0.1 x 0 is no stop
  EXPECT_FALSE(w.observe(when, 0.2, -50.0));  // the magnitude counts (a reaction may be negative)
  EXPECT_FALSE(w.observe(when, 0.5, 2.0));    // below 10 % of 50, but before after_time
  EXPECT_EQ(w.peak, 50.0);
  EXPECT_FALSE(w.observe(when, 1.0, 100.0));
  EXPECT_FALSE(w.observe(when, 1.5, 10.0));   // exactly 10 % of the peak is not below it
  EXPECT_TRUE(w.observe(when, 2.0, 9.99));
}

// The notched block of the paper's concrete pulled at 150 mm/s (tests/mpm/test_scenes.hpp) cracks
// and softens: with stop_when {top, 0.5} the run ends at the first row whose top reaction is
// below half the peak of the rows, and none before it is.
Scene softeningBlock() {
  Scene s = notchedCrackingBlock();
  s.endTime = 2e-3;  // far past what the block needs: the stop must end it
  s.outputInterval = 1e-5;
  s.stopWhen = StopWhen{"top", 0.5, 2e-5, {}, 0.0};
  return s;
}

TEST(StopWhen, EndsTheRunAtTheFirstRowBelowTheFractionOfThePeak) {
  TempDir tmp;
  const Scene s = softeningBlock();
  const RunResult r = runScene(s, quietRun(tmp.path()));
  ASSERT_TRUE(r.completed) << r.message();
  EXPECT_TRUE(r.endedByStopWhen);
  const io::CsvTable h = io::readCsv(tmp.path() / "history.csv");
  const auto col = static_cast<std::size_t>(std::find(h.header.begin(), h.header.end(), "top_ry_N") - h.header.begin());
  ASSERT_LT(col, h.header.size());
  double peak = 0.0;
  for (std::size_t i = 0; i + 1 < h.rows.size(); ++i) {
    peak = std::max(peak, std::abs(h.rows[i][col]));
    if (h.rows[i][0] >= 2e-5) {
      EXPECT_GE(std::abs(h.rows[i][col]), 0.5 * peak) << "row " << i << " should have stopped";
    }
  }
  const double last = std::abs(h.rows.back()[col]);
  EXPECT_LT(last, 0.5 * peak);
  EXPECT_LT(h.rows.back()[0], 0.5 * s.endTime) << "the block softens long before end_time";
  // Before softening the block carried about its ligament capacity f_t' b t = 3 x 80 x 1 = 240 N.
  EXPECT_GT(peak, 0.8 * 240.0) << "the block should have carried load before softening";
  const auto j = nlohmann::json::parse(readFile(tmp.path() / "summary.json"));
  EXPECT_EQ(j["status"], "completed");
  EXPECT_TRUE(j["stop_when"]["met"].get<bool>());
  EXPECT_EQ(j["stop_when"]["peak_of_rows_N"].get<double>(), peak);
  EXPECT_EQ(std::abs(j["stop_when"]["load_at_stop_N"].get<double>()), last);
  std::printf("[ stop_when ] peak of the rows %.1f N, stopped at t = %.3g s with %.1f N (%zu rows)\n", peak,
              h.rows.back()[0], last, h.rows.size());
}

// The watch's peak is part of the checkpoint: stopped after the peak and resumed, the run ends at
// the same row as the uninterrupted one, with the same files.
TEST(StopWhen, ARestartedRunStopsAtTheSameRow) {
  TempDir tmp;
  const Scene s = softeningBlock();
  const RunResult whole = runScene(s, quietRun(tmp.path() / "whole"));
  ASSERT_TRUE(whole.endedByStopWhen) << whole.message();
  RunOptions first = quietRun(tmp.path() / "split");
  first.maxSteps = whole.steps - 20;  // past the peak, a few rows before the stop
  ASSERT_TRUE(runScene(s, first).stopped);
  RunOptions second = quietRun(tmp.path() / "split");
  second.restart = true;
  const RunResult resumed = runScene(s, second);
  ASSERT_TRUE(resumed.endedByStopWhen) << resumed.message();
  EXPECT_EQ(resumed.steps, whole.steps);
  EXPECT_EQ(readFile(tmp.path() / "split" / "history.csv"), readFile(tmp.path() / "whole" / "history.csv"));
}

}  // namespace
}  // namespace ecm::mpm::test
