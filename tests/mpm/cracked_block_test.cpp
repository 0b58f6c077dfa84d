// A displacement-controlled block in uniaxial tension, run quasi-statically, cracks through its
// weakest row of cells and follows the closed form of the enriched point (the curve ecm-point
// traces for one point) within 1 %. With nu = 0 the block is one-dimensional; the row of cells y in
// [40, 50] has f_t' 1 % below the rest, so the crack localises there (linear shape functions:
// every particle of a cell sees the cell's strain). Elsewhere the block unloads elastically, so
// the top displacement is delta = sigma L / E + w(sigma), w the band's inelastic opening of the
// closed form (material/uniaxial_closed_form.hpp): independent of the cell size H, the point of
// the paper. L = 100 mm < h (E + E_p)/E_p = 195.6 mm, so the structure does not snap back.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "bar_closed_form.hpp"
#include "test_scenes.hpp"

namespace ecm::mpm::test {
namespace {

constexpr double kLength = 100.0, kWeakFt = 2.9, kEnd = 0.05;  // mm, MPa, mm

Scene crackingBlock(int cells) {
  const double h = kLength / cells;
  Scene s;
  s.name = "cracking-block";
  s.grid = {Vec2::Zero(), Vec2(h, h), cells, cells + 2};
  s.materials = concreteWithWeakRow(kWeakFt);
  s.bodies = {{Shape::rectangle(Vec2(0.0, 0.0), Vec2(kLength, kLength)), 0, false, Vec2::Zero()},
              {Shape::rectangle(Vec2(-1.0, 40.0), Vec2(kLength + 1.0, 50.0)), 1, false, Vec2::Zero()}};
  s.conditions = {NodeCondition::fixed("base", {Vec2(-1.0, 0.0), Vec2(kLength + 1.0, 0.0)}, false, true),
                  NodeCondition::fixed("corner", {Vec2(-1.0, -1.0), Vec2(0.0, 0.0)}, true, false)};
  NodeCondition top;
  top.name = "top";
  top.box = {Vec2(-1.0, kLength), Vec2(kLength + 1.0, kLength)};
  top.component[1] = {Prescribed::Displacement, TimeFunction::smoothRamp(kEnd, 2e-2)};  // ~750 wave transits
  s.conditions.push_back(top);
  s.solver.explicitScheme.damping.local = 0.2;
  s.solver.crackPath = CrackPathRule::Free;  // the weak row cracks where it stands, as the one point does
  s.endTime = 2e-2;
  return s;
}

TEST(CrackedBlock, QuasiStaticTensionFollowsTheEnrichedPointWithinOnePercent) {
  const DamageLawParams law{32000.0, kWeakFt, 8.184, 0.128};
  const BarClosedForm exact(law, kLength, 0.05, 2e-3);
  ASSERT_TRUE(std::is_sorted(exact.delta.begin(), exact.delta.end())) << "the closed form snaps back";
  ExplicitSolver solver(crackingBlock(10), 1);
  double worst = 0.0, worstAt = 0.0, peak = 0.0;
  int samples = 0;
  while (solver.time() < solver.scene().endTime) {
    solver.advance();
    if (solver.step() % 100) continue;
    const double delta = solver.conditions()[2].displacement[1];
    const double sigma = solver.conditions()[2].reaction[1] / (kLength * solver.scene().thickness);
    peak = std::max(peak, sigma);
    const double err = exact.distance(delta, sigma);
    if (err > worst) worst = err, worstAt = delta;
    ++samples;
  }
  const Particles& p = solver.particles();
  std::size_t crackedOutsideWeakRow = 0;
  for (std::size_t i = 0; i < p.size(); ++i)
    if (p.band[i] >= 0 && p.material[i] != 1) ++crackedOutsideWeakRow;
  // Dissipation: the weak row's bands (area b t, width h) from x = 1 to their final integrity.
  double xEnd = 1.0;
  for (std::size_t i = 0; i < p.size(); ++i)
    if (p.band[i] >= 0) xEnd = std::min(xEnd, p.bands[static_cast<std::size_t>(p.band[i])].integrity);
  const double dissipated = kLength * solver.scene().thickness * 0.05 * dissipationBetween(law, 1.0, xEnd);
  std::printf("[ cracked block ] %d samples, peak %.4f MPa (f_t' %.2f), worst distance to the closed form %.4f (f_t', f_t' L/E) at delta "
              "%.4f mm; dissipated %.5f N mm (closed form %.5f)\n",
              samples, peak, kWeakFt, worst, worstAt, solver.energies().dissipated, dissipated);
  EXPECT_LT(worst, 0.01);
  EXPECT_NEAR(peak, kWeakFt, 0.01 * kWeakFt);
  EXPECT_EQ(crackedOutsideWeakRow, 0u);
  EXPECT_NEAR(solver.energies().dissipated, dissipated, 0.01 * dissipated);
  EXPECT_LT(exact(kEnd), 0.5 * kWeakFt) << "the run should reach well into the softening branch";
}

}  // namespace
}  // namespace ecm::mpm::test
