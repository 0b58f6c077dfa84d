// Results do not depend on the thread count, bitwise: every node sums its particles in the fixed
// order of mpm/explicit/scatter_order.hpp (colour, block, particle index), every sum over particles or
// nodes is taken in fixed chunks (mpm/core/ordered_sum.hpp, the dissipation per chunk of the stress
// phase), and each particle's gather and update is its own. So the same scene on 1, 2 and 3
// threads gives the same bits, for every update scheme and shape function, through cracking.
#include <gtest/gtest.h>

#include <tuple>

#include "test_scenes.hpp"

namespace ecm::mpm::test {
namespace {

Scene crackingBlock(UpdateScheme scheme, ShapeFunction shape) {
  Scene s = notchedCrackingBlock();
  s.solver.explicitScheme.scheme = scheme;
  s.solver.shapeFunction = shape;
  return s;
}

void expectBitwiseEqual(const ExplicitSolver& a, const ExplicitSolver& b) {
  const Particles &p = a.particles(), &q = b.particles();
  ASSERT_EQ(p.bands.size(), q.bands.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    ASSERT_EQ(p.position[i], q.position[i]) << "particle " << i;
    ASSERT_EQ(p.velocity[i], q.velocity[i]) << "particle " << i;
    ASSERT_EQ(p.stress[i], q.stress[i]) << "particle " << i;
    ASSERT_EQ(p.band[i], q.band[i]) << "particle " << i;
  }
  const Energies e = a.energies(), f = b.energies();
  EXPECT_EQ(e.kinetic, f.kinetic);
  EXPECT_EQ(e.strain, f.strain);
  EXPECT_EQ(e.externalWork, f.externalWork);
  EXPECT_EQ(e.dissipated, f.dissipated);
  EXPECT_EQ(e.damping, f.damping);
  for (std::size_t c = 0; c < a.conditions().size(); ++c)
    EXPECT_EQ(a.conditions()[c].reaction, b.conditions()[c].reaction) << "condition " << c;
}

class ThreadCount : public ::testing::TestWithParam<std::tuple<UpdateScheme, ShapeFunction>> {};

TEST_P(ThreadCount, OneTwoAndThreeThreadsGiveTheSameBits) {
  const auto [scheme, shape] = GetParam();
  const Scene s = crackingBlock(scheme, shape);
  ExplicitSolver one(s, 1), two(s, 2), three(s, 3);
  ASSERT_EQ(three.threads(), 3);
  for (int n = 0; n < 200; ++n) {
    one.advance();
    two.advance();
    three.advance();
  }
  ASSERT_GT(one.particles().bands.size(), 0u) << "the block should have cracked";
  expectBitwiseEqual(one, two);
  expectBitwiseEqual(one, three);
}

INSTANTIATE_TEST_SUITE_P(
    SchemesAndShapes, ThreadCount,
    ::testing::Combine(::testing::Values(UpdateScheme::USL, UpdateScheme::MUSL, UpdateScheme::USF),
                       ::testing::Values(ShapeFunction::Linear, ShapeFunction::UGimp, ShapeFunction::BSpline2)),
    [](const auto& info) {
      return std::string(toString(std::get<0>(info.param))) + "_" + toString(std::get<1>(info.param));
    });

// A particle moved nine rows of cells between steps of the fused USL pass is outside the rows
// its chunk planned: the rebuild scatters it after the colours, alone. The results still do
// not depend on the thread count.
TEST(ThreadCount, AFarParticleScattersAloneWithTheSameBits) {
  const Scene s = crackingBlock(UpdateScheme::USL, ShapeFunction::Linear);
  ExplicitSolver one(s, 1), two(s, 2);
  for (ExplicitSolver* solver : {&one, &two}) {
    for (int n = 0; n < 20; ++n) solver->advance();
    const std::size_t moved = 300;
    const Vec2 x = solver->particles().position[moved] + Vec2(0.0, 45.0);  // nine 5 mm cells up
    solver->editParticles().position[moved] = x;
    const ScatterOrder& order = solver->state().order;
    const int row = static_cast<int>(std::floor((x[1] - s.grid.origin[1]) / s.grid.cellSize[1]));  // its base row (linear)
    ASSERT_GT(row, order.planned[moved / order.chunk].hi) << "the test needs a far particle";
    for (int n = 0; n < 20; ++n) solver->advance();
  }
  expectBitwiseEqual(one, two);
}

}  // namespace
}  // namespace ecm::mpm::test
