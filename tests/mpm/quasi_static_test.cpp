// Quasi-static elastic run: a block on a fixed base pulled by a total force F on its top row of
// particles. In equilibrium the base reaction is -F (statics), and with nu = 0 the stress below
// the loaded cell is uniaxial, sigma_yy = F / (b t), so u_y(y) = sigma y / E (Hooke's law). (In
// the top cell a particle load acts like a body force, so the closed form does not hold there.)
#include <gtest/gtest.h>

#include "test_scenes.hpp"

namespace ecm::mpm::test {
namespace {

TEST(QuasiStatic, ReactionEqualsAppliedLoadAndDisplacementMatchesHooke) {
  const double force = 1000.0;
  ExplicitSolver solver(tensionBlock(force), 1);
  while (solver.time() < solver.scene().endTime) solver.advance();
  const Vec2 reaction = solver.conditions()[0].reaction;
  EXPECT_NEAR(reaction[1], -force, 0.005 * force);
  EXPECT_NEAR(reaction[0], 0.0, 0.005 * force);
  EXPECT_NEAR(solver.loads()[0].applied[1], force, 1e-12 * force);

  const auto& p = solver.particles();
  const double sigma = force / (100.0 * 1.0), e = 32000.0;
  double worst = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.position[i][1] > 90.0) continue;  // the loaded cell
    const double exact = sigma * p.origin[i][1] / e;
    worst = std::max(worst, std::abs(p.displacement(i)[1] - exact) / (sigma * 100.0 / e));
    EXPECT_NEAR(p.stress[i][1], sigma, 0.01 * sigma) << "particle " << i;
  }
  EXPECT_LT(worst, 0.01);
  // Energy: work in = strain + kinetic + damped (to the accuracy of the explicit bookkeeping).
  const Energies en = solver.energies();
  const double balance = en.externalWork - en.strain - en.kinetic - en.damping;
  std::printf("[ quasi-static ] reaction %.4f N (load %.1f N), worst u_y error %.2e; energy: work %.5f strain %.5f "
              "kinetic %.2e damped %.5f, imbalance %.2e\n",
              reaction[1], force, worst, en.externalWork, en.strain, en.kinetic, en.damping, balance / en.externalWork);
  EXPECT_LT(std::abs(balance), 0.01 * en.externalWork);
}

TEST(QuasiStatic, PrescribedDisplacementReactionMatchesStiffness) {
  // Displacement control of the top nodes (smooth ramp to 0.01 mm): reaction = E A u / L.
  Scene s = tensionBlock(0.0);
  s.loads.clear();
  NodeCondition top;
  top.name = "top";
  top.box = {Vec2(-1.0, 100.0), Vec2(101.0, 100.0)};
  top.component[1] = {Prescribed::Displacement, TimeFunction::smoothRamp(0.01, 3e-4)};
  s.conditions.push_back(top);
  ExplicitSolver solver(s, 1);
  while (solver.time() < s.endTime) solver.advance();
  const double expected = 32000.0 * 100.0 * 0.01 / 100.0;  // E (b t) u / L = 32 N... per mm thickness
  EXPECT_NEAR(solver.conditions()[1].displacement[1], 0.01, 1e-15);
  EXPECT_NEAR(solver.conditions()[1].reaction[1], expected, 0.005 * expected);
  EXPECT_NEAR(solver.conditions()[0].reaction[1], -expected, 0.005 * expected);
}

}  // namespace
}  // namespace ecm::mpm::test
