// A homogeneous block whose grid nodes all follow one affine velocity field v = s(t) G x:
// every shape function here reproduces linear fields (sum_I grad N_I = 0, sum_I x_I (x) grad N_I = I),
// so each particle's strain increment is exactly dt s(t_{n+1}) sym(G), whatever its position.
// The stress history must then be that of calling the material update directly along the same
// strain path with the same effective size (independent computation: ecm::Material::update on a
// MaterialPoint), to 1e-6 relative.
#include <gtest/gtest.h>

#include <tuple>

#include "test_scenes.hpp"

namespace ecm::mpm::test {
namespace {

// 1/s: onset after ~100 steps, softening over the next ~1400.
constexpr double kRate = 3.0;

using Param = std::tuple<ShapeFunction, UpdateScheme, EffectiveSizeRule>;
class AffineField : public ::testing::TestWithParam<Param> {};

TEST_P(AffineField, EnrichedStressHistoryEqualsDirectMaterialUpdate) {
  const auto [shape, scheme, rule] = GetParam();
  Scene s;
  s.grid = {Vec2::Zero(), Vec2(10.0, 8.0), 6, 6};
  s.materials = {paperConcrete()};
  s.bodies = {{Shape::rectangle(Vec2(20.0, 16.0), Vec2(40.0, 32.0)), 0, false, Vec2::Zero()}};
  s.solver.shapeFunction = shape;
  s.solver.explicitScheme.scheme = scheme;
  s.solver.effectiveSize = rule;
  s.solver.crackPath = CrackPathRule::Free;  // a uniform field: every point cracks where it stands, as the one point does
  // Tension along x with shear: the crack normal is off the axes.
  Mat2 g;
  g << 1.0, 0.3, 0.1, -0.2;
  NodeCondition all;
  all.name = "all";
  all.box = {Vec2(-1.0, -1.0), Vec2(100.0, 100.0)};
  all.field = AffineVelocity{kRate * g, Vec2(30.0, 24.0), TimeFunction::smoothRamp(1.0, 2e-4)};
  s.conditions = {all};
  ExplicitSolver solver(s, 1);
  const Particles& p = solver.particles();
  ASSERT_GT(p.size(), 0u);

  const Material material(paperConcrete());
  const EffectiveSize size{rule, 0.0, 10.0, 8.0};
  MaterialPoint reference;
  const Voigt rate(g(0, 0), g(1, 1), g(0, 1) + g(1, 0));
  double worst = 0.0;
  bool cracked = false;
  int onsetStep = -1;
  double peak = 0.0, last = 0.0;
  for (int n = 0; n < 1500; ++n) {
    const double t = solver.time(), dt = solver.timeStep();
    solver.advance();
    solver.particles();  // (stores the stresses the step left unstored: p refers to them)
    const Voigt d = dt * kRate * all.field->scale(t + dt) * rate;
    const UpdateResult r = material.update(reference, d, size, SnapBackPolicy::Stop);
    ASSERT_TRUE(r.converged()) << "reference failed at step " << n;
    const double scale = std::max(r.stress.norm(), 1e-3 * 3.0);
    for (std::size_t i = 0; i < p.size(); ++i) {
      worst = std::max(worst, (p.stress[i] - r.stress).norm() / scale);
      ASSERT_NEAR(solver.damage(i), reference.damage(), 1e-6) << "particle " << i << " step " << n;
    }
    if (!cracked && reference.band) onsetStep = n;
    peak = std::max(peak, r.stress[0]);
    last = r.stress[0];
    cracked = cracked || reference.band.has_value();
  }
  EXPECT_TRUE(cracked);
  EXPECT_GT(onsetStep, 50);       // onset well inside the run, not in the first increment
  EXPECT_LT(last, 0.7 * peak);    // well into softening
  EXPECT_LT(worst, 1e-6);
  std::printf("[ affine ] %s/%s: onset at step %d, sigma_xx peak %.3f -> %.3f MPa, worst relative stress difference %.2e\n",
              toString(shape), toString(scheme), onsetStep, peak, last, worst);
}

INSTANTIATE_TEST_SUITE_P(
    All, AffineField,
    ::testing::Values(Param{ShapeFunction::Linear, UpdateScheme::USL, EffectiveSizeRule::SquareRoot},
                      Param{ShapeFunction::UGimp, UpdateScheme::MUSL, EffectiveSizeRule::Oriented},
                      Param{ShapeFunction::BSpline2, UpdateScheme::USF, EffectiveSizeRule::SquareRoot}),
    [](const auto& info) {
      return std::string(toString(std::get<0>(info.param))) + "_" + toString(std::get<1>(info.param));
    });

}  // namespace
}  // namespace ecm::mpm::test
