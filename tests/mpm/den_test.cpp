// The reduced DEN of the default suite: data/den/den-4b-coarse.yaml (Nooru-Mohamed's panel, load
// path 4b, 2.5 mm cells) run until the tensile load P has passed its peak and fallen to 90 % of
// it (about a third of the full path). Checks: cracking starts at the notch tips; the cracked
// set at the peak is nearly point symmetric about the panel centre (the loading is, up to the
// top edge being free in x while the bottom is held); the peak lies in the window measured by
// the full coarse run (scripts/den.sh, see the numbers below).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "mpm/scene/scene_yaml.hpp"
#include "mpm/explicit/explicit_solver.hpp"

namespace ecm::mpm::test {
namespace {

// The full coarse run (scripts/den.sh OUT coarse, 2 threads; summary.json peak_load): 18518.4 N.
// The same scene on one thread agrees to round-off (tests/mpm/threads_test.cpp), so the window
// only absorbs a change of the solver; 3 % is inside the 5 % mesh-objectivity criterion on the
// peak (docs/den.md, "The three meshes").
constexpr double kFullRunPeak = 18518.4;  // N
// At the peak of the full coarse run, the fraction of cracked particles whose 180-degree image is
// cracked too: 60.4 % of 1954 (this test's output line); the margin allows for a slightly
// different crack front.
constexpr double kSymmetry = 0.5;

TEST(Den, CoarsePanelCracksAtTheNotchTipsSymmetricallyAndPeaksInTheMeasuredWindow) {
  const Scene s = loadSceneFile(std::filesystem::path(ECM_SOURCE_DIR) / "data/den/den-4b-coarse.yaml");
  ExplicitSolver solver(s, 1);
  const Particles& p = solver.particles();
  ASSERT_EQ(s.conditions[2].name, "top");
  double peak = 0.0, peakDelta = 0.0;
  std::vector<Vec2> firstCracks;
  std::vector<bool> crackedAtPeak(p.size(), false);
  while (solver.time() < s.endTime) {
    solver.advance();
    if (firstCracks.empty() && !p.bands.empty())
      for (std::size_t i = 0; i < p.size(); ++i)
        if (p.band[i] >= 0) firstCracks.push_back(p.position[i]);
    const double load = solver.conditions()[2].reaction[1], delta = solver.conditions()[2].displacement[1];
    if (delta <= 0.0) continue;
    if (load > peak) {
      peak = load, peakDelta = delta;
      for (std::size_t i = 0; i < p.size(); ++i) crackedAtPeak[i] = p.band[i] >= 0;
    }
    if (peak > 5000.0 && load < 0.9 * peak) break;  // past the peak (P_s alone gives |P| << 5 kN)
  }
  // Onset: every first cracked point within 5 mm of a notch tip (the notch ends at x = 25 and
  // x = 175 between y = 97.5 and 102.5).
  ASSERT_FALSE(firstCracks.empty());
  for (const Vec2& x : firstCracks) {
    const double dLeft = std::hypot(std::max(0.0, x[0] - 25.0), std::max({0.0, 97.5 - x[1], x[1] - 102.5}));
    const double dRight = std::hypot(std::max(0.0, 175.0 - x[0]), std::max({0.0, 97.5 - x[1], x[1] - 102.5}));
    EXPECT_LT(std::min(dLeft, dRight), 5.0) << "first crack at (" << x[0] << ", " << x[1] << ")";
  }
  // Point symmetry: particles are seeded on a grid of spacing 1.25 mm, so the image of the seed
  // (i, j) is (159 - i, 159 - j); the current positions differ from the seeds by << 0.625 mm.
  std::map<std::pair<int, int>, std::size_t> at;
  const auto cell = [](const Vec2& x) { return std::make_pair(int(std::floor(x[0] / 1.25)), int(std::floor(x[1] / 1.25))); };
  for (std::size_t i = 0; i < p.size(); ++i) at[cell(p.position[i])] = i;
  std::size_t cracked = 0, mirrored = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (!crackedAtPeak[i]) continue;
    ++cracked;
    const auto [ci, cj] = cell(p.position[i]);
    const auto it = at.find({159 - ci, 159 - cj});
    if (it != at.end() && crackedAtPeak[it->second]) ++mirrored;
  }
  const double symmetry = double(mirrored) / double(cracked);
  std::printf("[ den ] first cracks: %zu points at the notch tips; peak P %.1f N at delta %.4f mm; %zu cracked at the "
              "peak, %.1f %% with a cracked 180-degree image\n",
              firstCracks.size(), peak, peakDelta, cracked, 100.0 * symmetry);
  EXPECT_GT(symmetry, kSymmetry);
  EXPECT_NEAR(peak, kFullRunPeak, 0.03 * kFullRunPeak);
}

// The fused USL pass (mpm/explicit/fused_transfer.cpp) is the plain USL phase sequence (P2G, grid, G2P,
// stress; ExplicitSolver::advanceByPhases, mpm/explicit/step.cpp) with its sums in another order: within a part
// it adds the closed-form points before the deferred ones. So the two agree to round-off, not
// bitwise: on the reduced DEN through its peak, the load history to 1e-12 of the peak and the
// same particles cracked.
TEST(Den, FusedUslPassAgreesWithThePlainPhaseSequenceThroughThePeak) {
  const Scene s = loadSceneFile(std::filesystem::path(ECM_SOURCE_DIR) / "data/den/den-4b-coarse.yaml");
  ASSERT_EQ(s.solver.explicitScheme.scheme, UpdateScheme::USL);
  ExplicitSolver fused(s, 1), plain(s, 1);  // one thread: ctest runs tests side by side
  double peak = 0.0, worst = 0.0;
  long steps = 0;
  while (fused.time() < s.endTime) {
    fused.advance();
    plain.advanceByPhases();
    ++steps;
    const double a = fused.conditions()[2].reaction[1], b = plain.conditions()[2].reaction[1];
    peak = std::max(peak, a);
    worst = std::max(worst, std::abs(a - b));
    if (peak > 5000.0 && a < 0.9 * peak) break;  // past the peak, as the test above
  }
  const Particles &p = fused.particles(), &q = plain.particles();
  std::size_t cracked = 0, same = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    cracked += p.band[i] >= 0 ? 1 : 0;
    same += (p.band[i] >= 0) == (q.band[i] >= 0) ? 1 : 0;
  }
  std::printf("[ den ] fused vs plain USL over %ld steps: largest load difference %.3g N (%.3g of the peak %.1f N), "
              "%zu cracked points\n",
              steps, worst, worst / peak, peak, cracked);
  ASSERT_GT(cracked, 500u) << "the panel should have cracked";
  EXPECT_EQ(same, p.size()) << "the same particles cracked";
  EXPECT_LE(worst, 1e-12 * peak);
  EXPECT_EQ(fused.particles().bands.size(), plain.particles().bands.size());
}

}  // namespace
}  // namespace ecm::mpm::test

namespace ecm::mpm {
namespace {
// The paper's DEN scenes carry the test's gauges (the LVDTs across the notches, 65 mm apart at the
// notch tips' x: data/validation/den-4b-rig-coarse.yaml), so that scripts/den.sh and paper.sh draw
// a run against the test with the test's delta, not the top edge's (its stiffness is 1.41 kN/um
// against the gauges' 2.93: docs/validation.md).
TEST(Den, ThePapersScenesCarryTheTestsGauges) {
  for (const char* mesh : {"coarse", "medium", "fine"}) {
    const Scene s = loadSceneFile(std::filesystem::path(ECM_SOURCE_DIR) / (std::string("data/den/den-4b-") + mesh + ".yaml"));
    ASSERT_EQ(s.gauges.size(), 2u) << mesh;
    for (const Gauge& g : s.gauges) {
      ASSERT_TRUE(g.to) << mesh;
      EXPECT_EQ(g.component, 1);
      EXPECT_DOUBLE_EQ(g.to->y() - g.at.y(), 65.0);
      EXPECT_TRUE(g.at.x() == 25.0 || g.at.x() == 175.0) << g.name;
    }
  }
}
}  // namespace
}  // namespace ecm::mpm
