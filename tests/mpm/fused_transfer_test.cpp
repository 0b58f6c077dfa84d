// The fused USL pass (mpm/explicit/fused_transfer.cpp) leaves in the grid the scatter of the particles
// for the next step. A grid rebuilt from the particles and the deferred list (what happens on
// the first step, after a restart or when the particles are touched between steps) must be
// bitwise that grid: otherwise a restarted run would drift from an uninterrupted one.
#include <gtest/gtest.h>

#include <utility>

#include "test_scenes.hpp"

namespace ecm::mpm::test {
namespace {

class FusedUsl : public ::testing::TestWithParam<ShapeFunction> {};

TEST_P(FusedUsl, RebuiltGridIsBitwiseTheFusedOne) {
  Scene scene = notchedCrackingBlock();
  scene.solver.shapeFunction = GetParam();
  ASSERT_EQ(scene.solver.explicitScheme.scheme, UpdateScheme::USL);
  ExplicitSolver fused(scene, 2), rebuilt(scene, 2);
  long deferredSteps = 0;
  for (int n = 0; n < 200; ++n) {
    fused.advance();
    rebuilt.rebuildGridNextStep();  // the next step scatters the particles anew (scatterState)
    rebuilt.advance();
    if (!fused.stepState().deferred.empty()) ++deferredSteps;
  }
  const Particles &a = fused.particles(), &b = rebuilt.particles();
  ASSERT_GT(a.bands.size(), 0u) << "the block should have cracked";
  ASSERT_GT(deferredSteps, 50) << "points should have been deferred (cracked or near onset)";
  EXPECT_EQ(a.bands.size(), b.bands.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(a.position[i], b.position[i]) << "particle " << i;
    ASSERT_EQ(a.velocity[i], b.velocity[i]) << "particle " << i;
    ASSERT_EQ(a.stress[i], b.stress[i]) << "particle " << i;
  }
  EXPECT_EQ(fused.energies().dissipated, rebuilt.energies().dissipated);
  EXPECT_EQ(fused.conditions()[1].reaction, rebuilt.conditions()[1].reaction);
}

INSTANTIATE_TEST_SUITE_P(Shapes, FusedUsl, ::testing::Values(ShapeFunction::Linear, ShapeFunction::UGimp));

}  // namespace
}  // namespace ecm::mpm::test
