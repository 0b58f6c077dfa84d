// Histories, shapes, seeding and the conservation properties of particle-to-grid.
#include <gtest/gtest.h>

#include <numbers>

#include "mpm/scene/unmeasured.hpp"
#include "mpm/setup/seeding.hpp"
#include "test_scenes.hpp"

namespace ecm::mpm::test {
namespace {

TEST(TimeFunction, Values) {
  EXPECT_DOUBLE_EQ(TimeFunction::hold(2.0)(5.0), 2.0);
  EXPECT_DOUBLE_EQ(TimeFunction::linearRamp(2.0, 1.0)(0.25), 0.5);
  EXPECT_DOUBLE_EQ(TimeFunction::linearRamp(2.0, 1.0)(3.0), 2.0);
  const TimeFunction s = TimeFunction::smoothRamp(2.0, 1.0);
  EXPECT_DOUBLE_EQ(s(0.0), 0.0);
  EXPECT_DOUBLE_EQ(s(0.5), 1.0);
  EXPECT_DOUBLE_EQ(s(1.0), 2.0);
  EXPECT_NEAR((s(1e-4) - s(0.0)) / 1e-4, 0.0, 1e-6);  // starts at rest
  const TimeFunction t = TimeFunction::table({0.0, 1.0, 3.0}, {0.0, 2.0, -2.0});
  EXPECT_DOUBLE_EQ(t(0.5), 1.0);
  EXPECT_DOUBLE_EQ(t(2.0), 0.0);
  EXPECT_DOUBLE_EQ(t(9.0), -2.0);
  EXPECT_THROW(TimeFunction::table({0.0, 0.0}, {1.0, 2.0}).validate(), std::invalid_argument);
}

// Tracked paths were measured with linear shape functions only (docs/model.md, "Crack paths",
// Limits): an enriched scene with tracked paths and another shape function is noted; linear
// shape functions, the free rule and a scene with no band (elastic) are not.
TEST(Unmeasured, TrackedPathsWithWideShapeFunctionsAreNotedForEnrichedScenesOnly) {
  Scene s = notchedCrackingBlock();
  s.solver.crackPath = CrackPathRule::Tracked;
  EXPECT_TRUE(unmeasuredCombinations(s).empty());
  for (const ShapeFunction wide : {ShapeFunction::UGimp, ShapeFunction::BSpline2}) {
    s.solver.shapeFunction = wide;
    const std::vector<std::string> notes = unmeasuredCombinations(s);
    ASSERT_EQ(notes.size(), 1u);
    EXPECT_NE(notes[0].find(std::string("shape_function: ") + toString(wide)), std::string::npos) << notes[0];
  }
  s.solver.crackPath = CrackPathRule::Free;
  EXPECT_TRUE(unmeasuredCombinations(s).empty());
  Scene elastic = tensionBlock();
  elastic.solver.crackPath = CrackPathRule::Tracked;
  elastic.solver.shapeFunction = ShapeFunction::UGimp;
  EXPECT_TRUE(unmeasuredCombinations(elastic).empty());
}

TEST(Geometry, PolygonAndCircle) {
  const Shape tri = Shape::polygon({Vec2(0, 0), Vec2(4, 0), Vec2(0, 4)});
  EXPECT_TRUE(tri.contains(Vec2(1, 1)));
  EXPECT_FALSE(tri.contains(Vec2(3, 3)));
  EXPECT_TRUE(Shape::circle(Vec2(1, 1), 1).contains(Vec2(1.5, 1.5)));
  EXPECT_FALSE(Shape::circle(Vec2(1, 1), 1).contains(Vec2(1.8, 1.8)));
}

TEST(Seeding, FillsShapesSubtractsHolesAndSetsVolumeAndMass) {
  Scene s;
  s.grid = {Vec2::Zero(), Vec2(1.0, 1.0), 100, 100};
  s.thickness = 2.0;
  s.particlesPerCell = 3;
  s.materials = {elasticMaterial(1000.0, 0.2, 1e-9), elasticMaterial(2000.0, 0.2, 3e-9)};
  s.bodies = {{Shape::rectangle(Vec2(10, 10), Vec2(90, 90)), 0, false, Vec2(1, 2)},
              {Shape::circle(Vec2(50, 50), 20), 0, true, Vec2::Zero()},   // hole
              {Shape::circle(Vec2(50, 50), 10), 1, false, Vec2::Zero()}};  // inclusion in the hole
  const Particles p = seedParticles(s);
  double area0 = 0.0, area1 = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    EXPECT_DOUBLE_EQ(p.volume[i], 2.0 / 9.0);
    const double a = p.volume[i] / s.thickness;
    (p.material[i] == 0 ? area0 : area1) += a;
    EXPECT_DOUBLE_EQ(p.mass[i], s.materials[p.material[i]].density * p.volume[i]);
  }
  const double pi = std::numbers::pi;
  EXPECT_NEAR(area0, 80.0 * 80.0 - pi * 400.0, 0.005 * area0);
  EXPECT_NEAR(area1, pi * 100.0, 0.01 * area1);
}

// Model only what the scene requires: materials listed but used by no particle change neither
// the memory per particle (the smeared crack's integrity array is not allocated) nor the time
// step (the wave speed of a stiffer unused material is ignored); a used one does.
TEST(Seeding, MaterialsNoParticleUsesCostNothing) {
  Scene s;
  s.grid = {Vec2::Zero(), Vec2(1.0, 1.0), 20, 20};
  s.materials = {elasticMaterial()};
  s.bodies = {{Shape::rectangle(Vec2(2, 2), Vec2(18, 18)), 0, false, Vec2::Zero()}};
  const ExplicitSolver plain(s, 1);

  MaterialParams smeared = paperConcrete();
  smeared.name = "smeared";
  smeared.model = ModelKind::SmearedCrack;
  smeared.fractureEnergy = 0.11;
  smeared.regularisedForSize = 1.0;
  MaterialParams stiff = paperConcrete();
  stiff.name = "stiff";
  stiff.elastic.youngsModulus = 200000.0;
  s.materials.push_back(smeared);
  s.materials.push_back(stiff);
  const ExplicitSolver listed(s, 1);
  EXPECT_EQ(listed.particles().bytesPerParticle(), plain.particles().bytesPerParticle());
  EXPECT_TRUE(listed.particles().integrity.empty());
  EXPECT_EQ(listed.timeStep(), plain.timeStep());

  s.bodies.push_back({Shape::rectangle(Vec2(2, 2), Vec2(4, 4)), 1, false, Vec2::Zero()});  // now used
  const ExplicitSolver used(s, 1);
  EXPECT_EQ(used.particles().bytesPerParticle(), plain.particles().bytesPerParticle() + sizeof(double));
}

TEST(ParticleToGrid, ConservesMassAndMomentumAndInternalForcesSumToZero) {
  for (ShapeFunction f : {ShapeFunction::Linear, ShapeFunction::UGimp, ShapeFunction::BSpline2}) {
    Scene s = tensionBlock();
    s.grid = {Vec2(-20.0, -20.0), Vec2(10.0, 10.0), 14, 14};
    s.conditions.clear();
    s.loads.clear();
    s.solver.shapeFunction = f;
    ExplicitSolver solver(s, 1);
    MpmState& st = solver.editState();
    Particles& p = st.particles;
    double mass = 0.0;
    Vec2 momentum = Vec2::Zero();
    for (std::size_t i = 0; i < p.size(); ++i) {
      p.velocity[i] = Vec2(std::sin(0.1 * i), std::cos(0.3 * i));
      p.stress[i] = Voigt(std::sin(0.2 * i), 0.5, -0.2 * std::cos(i));
      mass += p.mass[i];
      momentum += p.mass[i] * p.velocity[i];
    }
    particleToGrid(solver.setup(), 0, p, st.grid, st.order, kStencils | kMassMomentum | kForces);
    const auto& g = st.grid;
    double gm = 0.0;
    Vec2 gp = Vec2::Zero(), gf = Vec2::Zero();
    for (std::size_t n = 0; n < g.mass.size(); ++n) gm += g.mass[n], gp += g.momentum[n], gf += g.force[n];
    EXPECT_NEAR(gm, mass, 1e-13 * mass) << toString(f);
    EXPECT_NEAR((gp - momentum).norm(), 0.0, 1e-13 * mass) << toString(f);
    EXPECT_NEAR(gf.norm(), 0.0, 1e-10) << toString(f);  // sum grad N = 0
  }
}

}  // namespace
}  // namespace ecm::mpm::test
