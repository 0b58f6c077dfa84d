// The plots of a point run (driver/point_output.hpp): each stress against its own strain,
// legends only with the markers the run has, the second band's traction-opening curve, and
// titles that print numbers as written (H = 10 mm).
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "driver/point_output.hpp"
#include "driver/point_scene_yaml.hpp"

namespace ecm::driver {
namespace {

std::vector<std::string> titles(const io::PlotSpec& spec) {
  std::vector<std::string> t;
  for (const io::PlotSeries& s : spec.series) t.push_back(s.title);
  return t;
}
bool has(const io::PlotSpec& spec, const std::string& title) {
  const std::vector<std::string> t = titles(spec);
  return std::find(t.begin(), t.end(), title) != t.end();
}

TEST(PointPlots, UniaxialTensionShowsOnlyWhatHappens) {
  // H = 10 mm is far below the snap-back size (195.6 mm): no last stable state, so no such
  // marker; sig_yy = sig_xy = 0 are held, so only sig_xx is drawn.
  const PointScene s = loadPointScene(ECM_SOURCE_DIR "/data/point/uniaxial-tension-H10.yaml");
  const PointRun run = runPoint(s);
  ASSERT_TRUE(run.completed) << run.failure;
  const std::vector<io::PlotSpec> specs = pointPlotSpecs(s, run);
  ASSERT_EQ(specs.size(), 2u);
  EXPECT_EQ(specs[0].title, "uniaxial-tension-H10: stress-strain (H = 10 mm)");
  EXPECT_TRUE(has(specs[0], "sig_xx against eps_xx"));
  EXPECT_FALSE(has(specs[0], "sig_yy against eps_yy"));
  EXPECT_TRUE(has(specs[0], "onset"));
  EXPECT_FALSE(has(specs[0], "last stable state before a snap-back"));
  EXPECT_FALSE(has(specs[1], "last stable state before a snap-back"));
  EXPECT_FALSE(has(specs[1], "second band: n2.sigma.n2 vs jump [u]_2.n2"));
}

TEST(PointPlots, TheLockingPathPlotsSigYyAgainstEpsYyAndTheSecondBand) {
  // data/point/locking-second-band.yaml: eps_xx is held while eps_yy stretches, so sig_yy rises
  // and falls against eps_yy (against eps_xx it was a vertical line); the second band opens.
  const PointScene s = loadPointScene(ECM_SOURCE_DIR "/data/point/locking-second-band.yaml");
  const PointRun run = runPoint(s);
  ASSERT_TRUE(run.completed) << run.failure;
  const std::vector<io::PlotSpec> specs = pointPlotSpecs(s, run);
  EXPECT_EQ(specs[0].title, "locking-second-band: stress-strain (H = 2.5 mm)");
  EXPECT_TRUE(has(specs[0], "sig_yy against eps_yy"));
  for (const io::PlotSeries& p : specs[0].series)
    if (p.title == "sig_yy against eps_yy") {
      EXPECT_EQ(p.columns, "4:7");  // eps_yy, sig_yy of history.csv
    }
  EXPECT_TRUE(has(specs[1], "second band: n2.sigma.n2 vs jump [u]_2.n2"));
}

}  // namespace
}  // namespace ecm::driver
