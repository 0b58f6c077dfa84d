// A bar in uniaxial tension with the interface across its middle: the stress is uniform, so the
// model must follow the closed form delta = P L / (E A) + jump(P / A) on the softening branch
// (no snap-back: L / E below the law's steepest softening compliance), and dissipate the law's
// energy to failure times the area.
#include <gtest/gtest.h>

#include <cmath>

#include "cohesive/report.hpp"
#include "cohesive/scene.hpp"
#include "cohesive/solver.hpp"
#include "test_scenes.hpp"

namespace ecm::cohesive {
namespace {

using test::barScene;

constexpr double kArea = 100.0, kLength = 50.0, kE = 32000.0;

TEST(CohesiveBar, BandLawFollowsTheClosedFormOnTheSofteningBranch) {
  const Scene scene = barScene(LawKind::band, 0.12, 2e-4);
  const HalfModel model = buildModel(scene);
  ASSERT_EQ(model.mesh.elements.size(), 3u);  // 25 mm long half, one element through the height
  const SolveResult r = solveControlled(model, scene.law, scene.solver);
  // Closed form (material/ only, not this library's law code): on the monotonic branch at
  // integrity x, sigma = uniaxialStress(x), the jump h eps_L = h sigma / (x E). At each of the
  // model's steps on the softening branch x is found from sigma = P / A (bisection in log x:
  // sigma(x) decreases from f_t' at x = 1), and the closed form's delta compared with the model's.
  // Near the peak sigma(x) is flat (most damage happens close to f_t', calibration/README.md),
  // so only sigma < 0.95 f_t' is compared.
  const DamageLawParams& law = scene.law.band.law;
  int checked = 0;
  for (const StepRecord& h : r.history) {
    const double sigma = h.load / kArea;
    if (h.control < 0.005 || sigma > 0.95 * 3.0) continue;
    double lo = -40.0, hi = 0.0;  // log10 x
    for (int it = 0; it < 200; ++it) {
      const double mid = 0.5 * (lo + hi);
      (uniaxialStress(law, std::pow(10.0, mid)) > sigma ? hi : lo) = mid;
    }
    const double x = std::pow(10.0, 0.5 * (lo + hi));
    const double delta = sigma * kLength / kE + 0.05 * sigma / (x * kE);
    EXPECT_NEAR(h.control / delta, 1.0, 1e-8) << "sigma = " << sigma;
    ++checked;
  }
  EXPECT_GT(checked, 400);
}

TEST(CohesiveBar, HordijkFollowsTheClosedFormOnTheSofteningBranch) {
  const Scene scene = barScene(LawKind::hordijk, 0.25, 2e-4);
  const SolveResult r = solveControlled(buildModel(scene), scene.law, scene.solver);
  const HordijkInterface& p = scene.law.hordijk;
  for (double z : {0.02, 0.1, 0.3, 0.6, 0.9}) {
    const double w = z * p.criticalOpening(), sigma = hordijkTraction(p, w);
    const double delta = sigma * kLength / kE + w + sigma / p.initialStiffness;  // bulk + jump
    const auto load = loadAt(r.history, delta);
    ASSERT_TRUE(load.has_value());
    EXPECT_NEAR(*load / kArea, sigma, 2e-4 * 3.0) << "w / wc = " << z;
  }
}

TEST(CohesiveBar, DissipatesTheFractureEnergyTimesTheAreaAtCompleteFailure) {
  // Band law to delta = 1.5 mm: x ~ 1e-14, the energy left, ~x^(1-2n), is below 1e-9 of G_F.
  const Scene band = barScene(LawKind::band, 1.5, 5e-3);
  const SolveResult rb = solveControlled(buildModel(band), band.law, band.solver);
  EXPECT_NEAR(rb.history.back().dissipation / (bandFractureEnergy(band.law.band) * kArea), 1.0, 1e-4);
  EXPECT_NEAR(rb.history.back().dissipation / (0.11 * kArea), 1.0, 4e-4);  // the law gives 0.110036 N/mm
  // Hordijk past wc = 0.1885 mm: the area under the curve, 1.000768 G_F.
  const Scene hordijk = barScene(LawKind::hordijk, 0.3, 1e-3);
  const SolveResult rh = solveControlled(buildModel(hordijk), hordijk.law, hordijk.solver);
  EXPECT_NEAR(rh.history.back().dissipation / (hordijkAreaFactor() * 0.11 * kArea), 1.0, 1e-4);
  EXPECT_NEAR(rh.history.back().load, 0.0, 1e-9);
}

}  // namespace
}  // namespace ecm::cohesive
