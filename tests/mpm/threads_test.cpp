// Results do not depend on the thread count: the same scene on 1 and 2 threads agrees to 1e-12
// relative (per-thread grid buffers are summed in a fixed order; only nodes shared by two
// particle ranges see a different summation order).
#include <gtest/gtest.h>

#include "test_scenes.hpp"

namespace ecm::mpm::test {
namespace {

Scene crackingBlock(ShapeFunction shape) {
  Scene s = notchedCrackingBlock();
  s.solver.shapeFunction = shape;
  return s;
}

class ThreadCount : public ::testing::TestWithParam<ShapeFunction> {};

TEST_P(ThreadCount, OneAndTwoThreadsAgree) {
  Solver one(crackingBlock(GetParam()), 1), two(crackingBlock(GetParam()), 2);
  ASSERT_EQ(two.threads(), 2);
  for (int n = 0; n < 200; ++n) {
    one.advance();
    two.advance();
  }
  const auto &a = one.particles(), &b = two.particles();
  ASSERT_GT(a.bands.size(), 0u) << "the block should have cracked";
  EXPECT_EQ(a.bands.size(), b.bands.size());
  double stressScale = 0.0, dispScale = 0.0, velScale = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    stressScale = std::max(stressScale, a.stress[i].norm());
    dispScale = std::max(dispScale, a.displacement(i).norm());
    velScale = std::max(velScale, a.velocity[i].norm());
  }
  double ds = 0.0, du = 0.0, dv = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    ds = std::max(ds, (a.stress[i] - b.stress[i]).norm() / stressScale);
    du = std::max(du, (a.displacement(i) - b.displacement(i)).norm() / dispScale);
    dv = std::max(dv, (a.velocity[i] - b.velocity[i]).norm() / velScale);
    EXPECT_EQ(a.band[i] >= 0, b.band[i] >= 0);
  }
  const double dr = (one.conditions()[1].reaction - two.conditions()[1].reaction).norm() / one.conditions()[1].reaction.norm();
  std::printf("[ threads ] %s: %zu cracked of %zu; max relative differences: stress %.1e, displacement %.1e, velocity "
              "%.1e, reaction %.1e\n",
              toString(GetParam()), a.bands.size(), a.size(), ds, du, dv, dr);
  EXPECT_LT(ds, 1e-12);
  EXPECT_LT(du, 1e-12);
  EXPECT_LT(dv, 1e-12);
  EXPECT_LT(dr, 1e-12);
}

INSTANTIATE_TEST_SUITE_P(Shapes, ThreadCount, ::testing::Values(ShapeFunction::Linear, ShapeFunction::UGimp),
                         [](const auto& info) { return std::string(toString(info.param)); });

}  // namespace
}  // namespace ecm::mpm::test
