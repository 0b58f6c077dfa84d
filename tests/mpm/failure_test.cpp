// Failures are loud: a particle leaving the grid, a NaN, a material update that does not
// converge even after sub-stepping, and invalid scenes all stop with a message that names them.
#include <gtest/gtest.h>

#include <set>
#include <string_view>

#include "io/cli_exit.hpp"
#include "io/value_error.hpp"
#include "test_scenes.hpp"

namespace ecm::mpm::test {
namespace {

bool contains(const std::string& s, const std::string& needle) { return s.find(needle) != std::string::npos; }

// The failure kinds' table (mpm/core/errors.cpp): every kind once, each with its own name and its
// own exit status inside the range io/cli_exit.hpp gives failed runs, so a script can tell a
// failed run by the range and the kind by the status.
TEST(Failure, EachKindHasItsOwnNameAndExitStatusInTheFailedRunsRange) {
  std::set<std::string_view> names;
  std::set<int> statuses;
  for (std::size_t i = 0; i < kFailureKinds.size(); ++i) {
    const FailureKindInfo& k = kFailureKinds[i];
    EXPECT_EQ(static_cast<std::size_t>(k.kind), i) << k.name;  // in the enum's order: every kind listed
    EXPECT_EQ(&infoOf(k.kind), &k);
    EXPECT_FALSE(k.meaning.empty()) << k.name;
    names.insert(k.name);
    statuses.insert(k.exitStatus);
    EXPECT_GE(k.exitStatus, io::kExitFirstFailureKind) << k.name;
    EXPECT_LE(k.exitStatus, io::kExitLastFailureKind) << k.name;
  }
  EXPECT_EQ(names.size(), kFailureKinds.size());
  EXPECT_EQ(statuses.size(), kFailureKinds.size());
  EXPECT_EQ(static_cast<std::size_t>(FailureKind::Output) + 1, kFailureKinds.size());  // Output is the last kind
}

TEST(Failure, ParticleLeavingTheGridIsReportedWithIdPositionAndStep) {
  Scene s;
  s.grid = {Vec2::Zero(), Vec2(10.0, 10.0), 10, 4};
  s.materials = {elasticMaterial()};
  s.bodies = {{Shape::rectangle(Vec2(60.0, 10.0), Vec2(90.0, 30.0)), 0, false, Vec2(2e5, 0.0)}};  // 200 m/s to +x
  ExplicitSolver solver(s, 1);
  try {
    for (int n = 0; n < 10000; ++n) solver.advance();
    FAIL() << "no failure reported";
  } catch (const SimulationError& e) {
    EXPECT_EQ(e.kind, FailureKind::LeftGrid);
    EXPECT_GT(e.position[0], 100.0);
    EXPECT_GT(e.step, 10);
    EXPECT_EQ(e.step, solver.step());
    ASSERT_TRUE(e.particle);
    EXPECT_GT(solver.particles().position[*e.particle][0], 100.0);
    EXPECT_TRUE(contains(e.what(), "particle " + std::to_string(*e.particle))) << e.what();
    EXPECT_TRUE(contains(e.what(), "left the grid")) << e.what();
    EXPECT_TRUE(contains(e.what(), "step " + std::to_string(e.step))) << e.what();
  }
}

TEST(Failure, NanIsReportedWithStepAndParticle) {
  ExplicitSolver solver(tensionBlock(), 1);
  solver.advance();
  solver.editParticles().velocity[7] = Vec2(NAN, 0.0);
  try {
    solver.advance();
    FAIL() << "no failure reported";
  } catch (const SimulationError& e) {
    EXPECT_EQ(e.kind, FailureKind::NotFinite);
    EXPECT_EQ(e.step, 2);
    EXPECT_TRUE(contains(e.what(), "step 2: particle ")) << e.what();
  }
}

Scene snapBackBlock() {
  Scene s;
  s.grid = {Vec2::Zero(), Vec2(300.0, 300.0), 3, 3};
  s.materials = {paperConcrete()};
  s.bodies = {{Shape::rectangle(Vec2(300.0, 300.0), Vec2(600.0, 600.0)), 0, false, Vec2::Zero()}};
  NodeCondition all;
  all.name = "all";
  all.box = {Vec2(-1.0, -1.0), Vec2(1000.0, 1000.0)};
  Mat2 g = Mat2::Zero();
  g(0, 0) = 20.0;
  all.field = AffineVelocity{g, Vec2(450.0, 450.0), TimeFunction::hold(1.0)};
  s.conditions = {all};
  s.solver.crackPath = CrackPathRule::Free;  // every point cracks where it stands (the paper's rule)
  return s;
}

TEST(Failure, SnapBackIsReleasedByDefaultAndCounted) {
  ExplicitSolver solver(snapBackBlock(), 1);
  double peak = 0.0;
  int after = 0;
  for (int n = 0; n < 100000 && after < 10; ++n) {
    solver.advance();
    peak = std::max(peak, solver.particles().stress[0][0]);
    if (solver.particles().bands.size() == solver.particles().size()) ++after;
  }
  const Particles& p = solver.particles();
  ASSERT_EQ(p.bands.size(), p.size()) << "every point should have cracked";
  EXPECT_EQ(solver.snapBackReleases(), static_cast<long>(p.size()));  // each once, at onset
  // The first step already strains the block past onset (4.8e-4 > f_t'/E = 9.4e-5): the points
  // crack and release at once; their stress ends far below f_t' = 3 MPa, energy dissipated.
  EXPECT_LT(peak, 3.1);
  EXPECT_LT(p.stress[0][0], 1.0);
  EXPECT_GT(solver.energies().dissipated, 0.0);
}

TEST(Failure, SnapBackUnderTheStopPolicyStopsTheRunWithStatusAndResidual) {
  // Cells of 300 mm give H = 300 mm beyond the snap-back size h (E + E_p) / E_p = 195.5 mm:
  // no strain-controlled equilibrium exists after onset, sub-stepping cannot help. With
  // snap_back: stop the run stops there; by default (release) the points fail onto their
  // stable branch, are counted, and the run goes on.
  Scene s = snapBackBlock();
  s.solver.snapBack = SnapBackPolicy::Stop;
  ExplicitSolver solver(s, 1);
  try {
    for (int n = 0; n < 100000; ++n) solver.advance();
    FAIL() << "no failure reported";
  } catch (const SimulationError& e) {
    EXPECT_EQ(e.kind, FailureKind::SnapBack);
    EXPECT_EQ(e.status, UpdateStatus::SnapBack);
    ASSERT_TRUE(e.particle);
    EXPECT_TRUE(contains(e.what(), "particle " + std::to_string(*e.particle))) << e.what();
    EXPECT_TRUE(contains(e.what(), toString(e.status))) << e.what();
    EXPECT_TRUE(contains(e.what(), "residual")) << e.what();
    // A snap-back is a property of the path: not sub-stepped, and the message names the option.
    EXPECT_TRUE(contains(e.what(), "snap_back: stop")) << e.what();
    EXPECT_FALSE(contains(e.what(), "sub-steps")) << e.what();
    std::printf("[ failure ] %s\n", e.what());
  }
}

TEST(Failure, InvalidScenesAreRefusedWithTheKeyAndAReason) {
  // Scene::validate, the one checker: the key path names the value (the YAML reader reports it
  // at that key's line), the reason says what is wrong.
  auto refusal = [](const Scene& s) {
    try {
      s.validate();
    } catch (const io::ValueError& e) {
      return e.key + ": " + e.reason;
    }
    return std::string("nothing thrown");
  };
  Scene s = tensionBlock();
  s.solver.explicitScheme.cfl = 1.2;
  EXPECT_EQ(refusal(s), "solver.cfl: 1.2 is outside the allowed range (0, 1]");
  s = tensionBlock();
  s.materials[0].density = 0.0;
  EXPECT_TRUE(contains(refusal(s), "materials[0]: material 'elastic': MPM needs density > 0")) << refusal(s);
  s = tensionBlock();
  s.conditions[0].box = {Vec2(-50.0, -50.0), Vec2(-40.0, -40.0)};
  EXPECT_EQ(refusal(s), "conditions[0].box: contains no grid node");
  s = tensionBlock();
  s.loads[0].history = TimeFunction::smoothRamp(1.0, -1.0);
  EXPECT_TRUE(contains(refusal(s), "loads[0].history: ") && contains(refusal(s), "ramp time")) << refusal(s);
  EXPECT_EQ(refusal(tensionBlock()), "nothing thrown");
}

TEST(Failure, ParticlesTooCloseToTheGridEdgeForTheShapeFunctionAreRefusedBySeeding) {
  // Where the particles sit is known only once they are seeded: the solver refuses it.
  Scene s = tensionBlock();
  s.solver.shapeFunction = ShapeFunction::BSpline2;
  try {
    ExplicitSolver solver(s, 1);
    FAIL() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_TRUE(contains(e.what(), "within 1.5 cells of the grid edge")) << e.what();
  }
}

}  // namespace
}  // namespace ecm::mpm::test
