// ecm-mpm with the second-band option (docs/model.md, "A second band"): second bands open where
// the bulk along a crack goes into tension, every point keeps traction continuity on both
// bands, the run's outputs show them, and the result does not depend on the thread count.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "../io/temp_dir.hpp"
#include "io/csv_reader.hpp"
#include "mpm/run.hpp"
#include "test_scenes.hpp"
#include "run_helpers.hpp"

namespace ecm::mpm::test {
namespace {

using namespace ecm::test;  // readFile, TempDir

TEST(SecondBandRun, OpensSecondBandsAndWritesThem) {
  TempDir tmp;
  const Scene s = twoBandBlock();
  RunOptions o = quietRun(tmp.path() / "out");
  o.snapshots = true;
  o.threads = 2;
  const RunResult r = runScene(s, o);
  ASSERT_TRUE(r.completed) << r.message();
  const auto j = nlohmann::json::parse(readFile(o.outputDir / "summary.json"));
  ASSERT_TRUE(j.contains("two_band_points"));
  const int twoBands = j["two_band_points"];
  EXPECT_GT(twoBands, 0);
  EXPECT_EQ(j["bytes_per_particle_two_bands"], j["bytes_per_particle_cracked"].get<int>() + sizeof(BandState));
  const io::CsvTable p = io::readCsv(o.outputDir / "particles_final.csv");
  ASSERT_EQ(p.header.size(), 14u);
  EXPECT_EQ(p.header[10], "damage_2");
  int withSecond = 0;
  for (const auto& row : p.rows) {
    if (row[10] <= 0.0) continue;
    ++withSecond;
    // The second band's normal is the first band's tangent.
    EXPECT_NEAR(row[5] * row[12] + row[6] * row[13], 0.0, 1e-12);
  }
  EXPECT_GT(withSecond, 0);
  EXPECT_LE(withSecond, twoBands);
  EXPECT_NE(readFile(o.outputDir / "particles_00012.vtu").find("Name=\"damage_2\""), std::string::npos);
}

TEST(SecondBandRun, KeepsContinuityOnBothBandsAndIsIndependentOfTheThreads) {
  const Scene s = twoBandBlock();
  ExplicitSolver one(s, 1), two(s, 2);
  while (one.time() < s.endTime) {
    one.advance();
    two.advance();
  }
  const Particles& p = one.particles();
  ASSERT_FALSE(p.secondBands.empty());
  const TwoPhasePoint& m = *one.materials()[0].enriched();
  for (std::size_t i = 0; i < p.size(); ++i) {
    const BandState* second = p.secondBandOf(i);
    if (!second) continue;
    const BandState& first = p.bands[static_cast<std::size_t>(p.band[i])];
    const BandDamageLaw::LoadingSurface frozen[2] = {{first.integrity, INFINITY}, {second->integrity, INFINITY}};
    Vec4 jumps;
    jumps << first.jump, second->jump;
    const TwoBandEquilibrium eq = m.equilibrium(first, *second, frozen, p.strain[i], jumps, false);
    EXPECT_LE(eq.residual.norm(), 1e-9 * 3.0 + 1e-13 * (m.stiffness() * p.strain[i]).norm()) << "particle " << i;
    EXPECT_LE((eq.stress - p.stress[i]).norm(), 1e-9 * 3.0) << "particle " << i;
  }
  // The same second bands on any thread count (new bands are added in particle order).
  EXPECT_EQ(p.secondBand, two.particles().secondBand);
  EXPECT_EQ(p.secondBands.size(), two.particles().secondBands.size());
}

}  // namespace
}  // namespace ecm::mpm::test
