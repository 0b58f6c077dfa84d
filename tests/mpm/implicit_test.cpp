// The implicit quasi-static solver (mpm/implicit/implicit_solver.hpp). Expected values: the patch test
// (a uniform strain is an exact solution of the discrete equations when the particles integrate
// the shape functions' gradients exactly, as regular 2 x 2 seeding does for every shape function
// here), central differences of the assembled internal force for the tangent, and elasticity in
// closed form (a block in uniaxial tension: delta = F L / (E A)).
#include <gtest/gtest.h>

#include <Eigen/SparseLU>
#include <algorithm>
#include <cmath>
#include <filesystem>

#include "bar_closed_form.hpp"
#include "mpm/implicit/amg_solver.hpp"
#include "mpm/implicit/implicit_solver.hpp"
#include "mpm/implicit/newton_cycle.hpp"
#include "mpm/implicit/newton_ends.hpp"
#include "mpm/scene/scene_yaml.hpp"
#include "test_scenes.hpp"

namespace ecm::mpm::test {
namespace {

// A block over cells [3, 9] x [3, 9] of a 12 x 12 grid of 1 mm cells; the nodes within one node
// of the block's edge take the affine displacement u = G x, the 9 inner ones are unknowns.
Scene patchScene(ShapeFunction shape, const Mat2& gradient) {
  Scene s;
  s.name = "patch";
  s.grid = {Vec2::Zero(), Vec2(1.0, 1.0), 12, 12};
  s.materials = {elasticMaterial(1000.0, 0.25)};
  s.bodies = {{Shape::rectangle(Vec2(3.0, 3.0), Vec2(9.0, 9.0)), 0, false, Vec2::Zero()}};
  s.particlesPerCell = 2;
  s.solver.shapeFunction = shape;
  const Box bands[] = {{Vec2(-1, -1), Vec2(13, 4.5)}, {Vec2(-1, 7.5), Vec2(13, 13)}, {Vec2(-1, -1), Vec2(4.5, 13)},
                       {Vec2(7.5, -1), Vec2(13, 13)}};
  for (const Box& b : bands) {
    NodeCondition c;
    c.name = "edge" + std::to_string(s.conditions.size());
    c.box = b;
    c.field = AffineVelocity{gradient, Vec2::Zero(), TimeFunction::hold(1.0)};
    s.conditions.push_back(c);
  }
  s.endTime = 1.0;
  s.solver.crackPath = CrackPathRule::Free;  // the weak row cracks where it stands (the paper's rule)
  return s;
}

class ImplicitPatch : public ::testing::TestWithParam<ShapeFunction> {};

TEST_P(ImplicitPatch, AUniformStrainIsReproducedExactly) {
  Mat2 g;
  g << 1e-3, 4e-4, 1e-4, -5e-4;  // du = G x over the step (dt = 1 s): eps = (1e-3, -5e-4, 5e-4)
  ImplicitSolver solver(patchScene(GetParam(), g));
  const ImplicitStepReport r = solver.step(1.0);
  EXPECT_LE(r.iterations, 1);  // linear: one Newton step
  const Voigt expected(1e-3, -5e-4, 5e-4);
  const Particles& p = solver.particles();
  const Tangent c = solver.setup().materials[0].stiffness();
  for (std::size_t i = 0; i < p.size(); ++i) {
    for (int k = 0; k < 3; ++k) ASSERT_NEAR(p.strain[i][k], expected[k], 1e-15) << "particle " << i;
    const Voigt s = c * expected;
    for (int k = 0; k < 3; ++k) ASSERT_NEAR(p.stress[i][k], s[k], 1e-12);
    const Vec2 u = p.displacement(i), x0 = p.origin[i];
    ASSERT_NEAR((u - g * x0).norm(), 0.0, 1e-14);  // the particles moved with the field
  }
}

INSTANTIATE_TEST_SUITE_P(EveryShapeFunction, ImplicitPatch,
                         ::testing::Values(ShapeFunction::Linear, ShapeFunction::UGimp, ShapeFunction::BSpline2),
                         [](const auto& info) { return std::string(toString(info.param)); });

// A block 100 x 100 mm on a fixed base pulled by a load on its top row of particles, nu = 0: a
// bar, delta = F L / (E A) (A = 100 mm x 1 mm of thickness), exactly as the grid spreads the load.
TEST(Implicit, ABlockUnderALoadStretchesAsElasticityGives) {
  Scene s = tensionBlock(1000.0, 10);
  s.solver.explicitScheme.damping.local = 0.0;
  s.loads[0].history = TimeFunction::linearRamp(1.0, 1.0);  // pseudo-time: the load factor goes 0 -> 1 over [0, 1]
  s.endTime = 1.0;
  ImplicitSolver solver(s);
  solver.step(1.0);  // one step: the particles move only at its end
  double top = 0.0;
  int n = 0;
  const Particles& p = solver.particles();
  for (std::size_t i = 0; i < p.size(); ++i)
    if (p.origin[i][1] > 95.0) top += p.displacement(i)[1], ++n;
  top /= n;
  // The discrete answer: the load reaches the nodes at y = 90 and 100 with the top row's weights
  // 1/4 and 3/4, so u(90) = 90 F/(E A), u(100) = u(90) + (3/4) 10 F/(E A), and the top row at
  // y = 97.5 moves 1/4 u(90) + 3/4 u(100) = 95.625 F/(E A) (97.5 F/(E A) in the continuum).
  const double strain = 1000.0 / (32000.0 * 100.0 * s.thickness);
  EXPECT_NEAR(top / (strain * 95.625), 1.0, 1e-9);
  // Equilibrium: the base's reaction balances the load.
  EXPECT_NEAR(solver.conditions()[0].reaction[1], -1000.0, 1e-6 * 1000.0);
  // Work = stored energy (elastic).
  const Energies e = solver.energies();
  EXPECT_NEAR(e.externalWork, e.strain, 1e-3 * e.strain);
}

// Pure bending of a beam 100 x 20 mm (nu = 0) by its ends: x = 0 held, x = L turned by the
// affine field u = (-kappa L y, kappa L x / 2) of the exact solution u = (-kappa x y, kappa x^2 / 2)
// (elasticity: sigma_xx = -E kappa y, no shear). Bilinear shape functions cannot carry x^2: each
// cell adds a parasitic shear of order kappa h, so the strain energy exceeds the exact
// U = E kappa^2 I L / 2 by a relative error of order (h / D)^2. Measured (docs/implicit.md):
// 3.125, 0.781, 0.195, 0.0488 % at D/h = 2, 4, 8, 16 (exactly (h/D)^2 / 8), order 2.000.
Scene bendingBeam(double h) {
  const double length = 100.0, depth = 20.0, kappa = 1e-5;  // mm, mm, 1/mm
  Scene s;
  s.name = "bending";
  s.grid = {Vec2(-h, -0.5 * depth - h), Vec2(h, h), static_cast<int>(std::lround(length / h)) + 2,
            static_cast<int>(std::lround(depth / h)) + 2};
  s.materials = {elasticMaterial(1000.0, 0.0)};
  s.bodies = {{Shape::rectangle(Vec2(0.0, -0.5 * depth), Vec2(length, 0.5 * depth)), 0, false, Vec2::Zero()}};
  s.particlesPerCell = 2;
  NodeCondition held;
  held.name = "held";
  held.box = {Vec2(-2.0 * h, -depth), Vec2(0.0, depth)};
  held.component[0].kind = held.component[1].kind = Prescribed::Fixed;
  NodeCondition turned;
  turned.name = "turned";
  turned.box = {Vec2(length, -depth), Vec2(length + 2.0 * h, depth)};
  Mat2 g;
  g << 0.0, -kappa * length, 0.5 * kappa * length, 0.0;
  turned.field = AffineVelocity{g, Vec2::Zero(), TimeFunction::hold(1.0)};
  s.conditions = {held, turned};
  s.endTime = 1.0;
  return s;
}

TEST(Implicit, PureBendingConvergesToElasticityAtSecondOrder) {
  const double exact = 0.5 * 1000.0 * 1e-10 * (20.0 * 20.0 * 20.0 / 12.0) * 100.0;  // E kappa^2 I L / 2, 1 mm thick
  std::vector<double> errors;
  for (const double h : {10.0, 5.0, 2.5, 1.25}) {
    ImplicitSolver solver(bendingBeam(h));
    solver.step(1.0);
    errors.push_back(solver.energies().strain / exact - 1.0);
    std::printf("D/h = %4.0f: strain energy %.6e N mm, exact %.6e, relative error %.4e\n", 20.0 / h,
                solver.energies().strain, exact, errors.back());
  }
  for (std::size_t k = 0; k + 1 < errors.size(); ++k) {
    ASSERT_GT(errors[k + 1], 0.0);  // a displacement method overestimates the stiffness
    const double order = std::log2(errors[k] / errors[k + 1]);
    std::printf("observed order %.3f\n", order);
    EXPECT_NEAR(order, 2.0, 0.1);
  }
  EXPECT_LT(errors.back(), 5e-3);
}

// The assembled tangent against central differences of the assembled internal force, on a
// notched block of the paper's concrete pulled past cracking: cracked points loading and
// unloading, and intact ones, all in the scene.
// The cycle guard's rule (mpm/implicit/newton_cycle.hpp): points that switch between loading and
// unloading while the residual grows after a fresh tangent are flagged for the secant tangent;
// a stale tangent's growth flags nothing (it is the factorisation's age, not a kink); the flags
// go once the residual has fallen kSettled times in a row.
TEST(Implicit, TheCycleGuardFlagsThePointsThatSwitchWhileTheResidualGrows) {
  CycleGuard guard;
  const std::vector<double> a{0.0, 1e-3, 0.0, 2e-3}, b{1e-3, 1e-3, 0.0, 0.0}, c{0.0, 1e-3, 0.0, 0.0};
  guard.solvedWithFreshTangent(true);
  guard.observe(a, 1e-3);
  EXPECT_EQ(guard.secantFlags(), nullptr);  // a first iterate: nothing to compare with
  guard.solvedWithFreshTangent(false);
  guard.observe(b, 2e-3);
  EXPECT_EQ(guard.secantFlags(), nullptr) << "grew after a stale tangent";
  guard.solvedWithFreshTangent(true);
  guard.observe(a, 1e-3);
  EXPECT_EQ(guard.secantFlags(), nullptr) << "fell";
  guard.observe(b, 3e-3);  // grew after a fresh tangent: points 0 and 3 switched
  ASSERT_NE(guard.secantFlags(), nullptr);
  EXPECT_EQ(*guard.secantFlags(), (std::vector<std::uint8_t>{1, 0, 0, 1}));
  guard.observe(c, 4e-3);  // point 0 switched back: still flagged, nothing new
  EXPECT_EQ(*guard.secantFlags(), (std::vector<std::uint8_t>{1, 0, 0, 1}));
  for (int k = 1; k < CycleGuard::kSettled; ++k) {
    guard.observe(c, 4e-3 / (k + 1));
    ASSERT_NE(guard.secantFlags(), nullptr) << k;
  }
  guard.observe(c, 1e-4);  // the kSettled-th fall
  EXPECT_EQ(guard.secantFlags(), nullptr);
}

// When Newton gives up early (mpm/implicit/newton_ends.hpp). The residuals are those of load step
// 193 of the coarse second-band DEN on a path moved by round-off (docs/implicit.md, "Load
// steps"): Newton with the kept factorisation stalled near 2.4e-3, came back from a spike of 0.17
// (67 times its lowest), then jumped to 0.82 (350 times): diverged there, not at the spike. A
// load-controlled start (1.0 at du = 0, then 0.6) has not diverged: it never was lower.
TEST(Implicit, NewtonEndsWhereItLeavesItsBasinOrStalls) {
  std::vector<double> r{7.941e-3, 9.927e-2, 7.234e-3, 2.620e-3, 2.603e-3, 2.599e-3, 1.735e-1};
  EXPECT_FALSE(diverged(r)) << "the spike, 67 times the lowest";
  for (const double next : {6.847e-3, 2.594e-3, 2.370e-3, 2.348e-3}) {
    r.push_back(next);
    EXPECT_FALSE(diverged(r)) << next;
  }
  r.push_back(8.245e-1);
  EXPECT_TRUE(diverged(r));
  EXPECT_FALSE(diverged({1.0}));
  EXPECT_FALSE(diverged({1.0, 0.6}));
  EXPECT_FALSE(diverged({1e-3, 0.4})) << "below kDivergedResidual";
  // Stalled: the residual did not halve over kStallWindow iterations.
  EXPECT_TRUE(stalled({1e-3, 9e-4, 8e-4, 7e-4, 6e-4, 6e-4, 5.5e-4}));
  EXPECT_FALSE(stalled({1e-3, 9e-4, 8e-4, 7e-4, 6e-4, 6e-4, 4.9e-4}));
  EXPECT_FALSE(stalled({1e-3, 1e-3, 1e-3, 1e-3, 1e-3, 1e-3})) << "fewer than kStallWindow + 1 iterates";
}

// Releases kept within an attempt (docs/implicit.md, "Releases kept within a step"). The notched
// block in a concrete whose points snap back at its cell size (E_p = 400 MPa: the snap-back size
// h (E + E_p) / E_p = 0.05 x 32400 / 400 = 4.05 mm is below H = 5 mm; docs/model.md, "Snap-back
// on the path") takes one trial of twice the onset strain f_t' / E along y in its left 10 mm
// (0.6 times it further right): the points there crack, snap back and are released. Kept, a
// released point starts the attempt's later trials from its released state: the same du again
// gives its stress and dissipation again, with no new release; half the du unloads it from its
// released damage (its integrity stays), where from the committed (intact) state it would not
// have failed so far.
TEST(Implicit, AKeptReleaseStartsThePointsLaterTrialsFromItsReleasedState) {
  Scene s = notchedCrackingBlock();
  s.materials[0].softeningModulus = 400.0;
  const ImplicitSolver solver(s);
  const Particles& p = solver.particles();
  std::vector<std::uint8_t> prescribed(static_cast<std::size_t>(2 * s.grid.nodeCount()), 0);
  for (const auto node : solver.conditions()[0].nodes)
    prescribed[2 * static_cast<std::size_t>(node)] = prescribed[2 * static_cast<std::size_t>(node) + 1] = 1;
  StepGeometry g;
  std::size_t outside = 0;
  ASSERT_TRUE(stepGeometry(solver.setup(), p, prescribed, g, outside));
  const double strain = 2.0 * ecm::test::kFt / ecm::test::kE;
  Eigen::VectorXd du = Eigen::VectorXd::Zero(2 * s.grid.nodeCount());
  for (int n = 0; n < s.grid.nodeCount(); ++n) {
    const Vec2 x = s.grid.nodePosition(n);
    du[2 * n + 1] = (x.x() <= 10.0 ? 1.0 : 0.3) * strain * x.y();
  }
  const ReleasedStarts none;
  Trial released;
  evaluateTrial(solver.setup(), p, g, du, false, SnapBackPolicy::Release, released, nullptr, nullptr, &none);
  ASSERT_EQ(released.failed, SIZE_MAX);
  ASSERT_GT(released.released, 0);
  EXPECT_LT(released.released, static_cast<long>(p.size()) / 4);  // the left strip only (a short test under sanitizers)
  ASSERT_EQ(static_cast<long>(released.releases.size()), released.released);
  EXPECT_TRUE(std::is_sorted(released.releases.begin(), released.releases.end(),
                             [](const auto& a, const auto& b) { return a.first < b.first; }));
  ReleasedStarts kept;
  keepReleases(released, p.size(), kept);
  ASSERT_EQ(kept.starts.size(), released.releases.size());
  Trial again, half, halfFromCommitted;
  evaluateTrial(solver.setup(), p, g, du, false, SnapBackPolicy::Release, again, nullptr, nullptr, &kept);
  evaluateTrial(solver.setup(), p, g, 0.5 * du, false, SnapBackPolicy::Release, half, nullptr, nullptr, &kept);
  evaluateTrial(solver.setup(), p, g, 0.5 * du, false, SnapBackPolicy::Release, halfFromCommitted);
  ASSERT_EQ(again.failed, SIZE_MAX);
  ASSERT_EQ(half.failed, SIZE_MAX);
  ASSERT_EQ(halfFromCommitted.failed, SIZE_MAX);
  EXPECT_EQ(again.released, 0);
  EXPECT_EQ(half.released, 0);
  EXPECT_NEAR((again.internalForce - released.internalForce).norm(), 0.0, 1e-9 * released.internalForce.norm());
  for (const auto& [i, start] : released.releases) {
    ASSERT_GE(kept.of[i], 0) << i;
    EXPECT_EQ(kept.starts[static_cast<std::size_t>(kept.of[i])].dissipation, start.dissipation) << i;
    ASSERT_TRUE(start.band.has_value());
    EXPECT_LT((again.stress[i] - released.stress[i]).norm(), 1e-9 * ecm::test::kFt) << i;
    EXPECT_NEAR(again.dissipation[i], released.dissipation[i], 1e-12 * released.dissipation[i]) << i;
    EXPECT_GT(released.dissipation[i], 0.0) << i;
    ASSERT_TRUE(half.band[i].has_value());
    EXPECT_EQ(half.band[i]->integrity, start.band->integrity) << i;  // unloading: the damage kept
    EXPECT_EQ(half.dissipation[i], released.dissipation[i]) << i;
    const double committedPath = halfFromCommitted.band[i] ? halfFromCommitted.band[i]->integrity : 1.0;
    EXPECT_GT(committedPath, start.band->integrity) << i;
  }
  // A point released again later in the attempt gets its new start; the others keep theirs.
  Trial later;
  const std::size_t first = released.releases.front().first;
  ReleasedStart again1 = released.releases.front().second;
  again1.dissipation += 1.0;
  later.releases.emplace_back(first, again1);
  keepReleases(later, p.size(), kept);
  EXPECT_EQ(kept.starts.size(), released.releases.size());
  EXPECT_EQ(kept.starts[static_cast<std::size_t>(kept.of[first])].dissipation, again1.dissipation);
}

TEST(Implicit, TheAssembledTangentIsTheDerivativeOfTheInternalForce) {
  Scene s = notchedCrackingBlock();
  s.conditions[1].component[1].kind = Prescribed::Displacement;  // the top row: displacement in pseudo-time
  s.conditions[1].component[1].history = TimeFunction::linearRamp(0.03, 1.0);
  ImplicitSolver solver(s);
  for (int k = 0; k < 3; ++k) solver.step(0.1);
  const Particles& p = solver.particles();
  long cracked = 0;
  for (const auto b : p.band) cracked += b >= 0 ? 1 : 0;
  ASSERT_GT(cracked, 0) << "the block should have cracked";
  std::printf("cracked points: %ld\n", cracked);
  // The geometry of a next step, and a trial du near it.
  std::vector<std::uint8_t> prescribed(static_cast<std::size_t>(2 * s.grid.nodeCount()), 0);
  for (const auto node : solver.conditions()[0].nodes)  // the base: x and y
    prescribed[2 * static_cast<std::size_t>(node)] = prescribed[2 * static_cast<std::size_t>(node) + 1] = 1;
  for (const auto node : solver.conditions()[1].nodes) prescribed[2 * static_cast<std::size_t>(node) + 1] = 1;  // the top: y
  StepGeometry g;
  std::size_t outside = 0;
  ASSERT_TRUE(stepGeometry(solver.setup(), p, prescribed, g, outside));
  // A trial du of mixed signs, 1e-7 mm: cracked points load and unload. (At 1e-5 mm some
  // intact points reach onset inside the trial; their tangent is the cracked one at the end,
  // which leaves out how onset moves with the increment: 0.4 % of E, docs/implicit.md.)
  const double kAmplitude = 1e-7;
  Eigen::VectorXd du = Eigen::VectorXd::Zero(2 * s.grid.nodeCount());
  for (int u = 0; u < g.dofs.unknowns(); ++u) du[g.dofs.component[static_cast<std::size_t>(u)]] = kAmplitude * std::sin(0.37 * u);
  Trial base;
  evaluateTrial(solver.setup(), p, g, du, true, SnapBackPolicy::Stop, base);
  ASSERT_EQ(base.failed, SIZE_MAX);
  int loading = 0, unloading = 0;
  for (std::size_t i = 0; i < p.size(); ++i)
    if (p.band[i] >= 0) (base.band[i]->integrity < p.bands[static_cast<std::size_t>(p.band[i])].integrity ? loading : unloading)++;
  EXPECT_GT(loading, 0);
  EXPECT_GT(unloading, 0);
  const Eigen::MatrixXd k(base.tangent);
  // Central differences where the internal force is smooth: a column whose one-sided differences
  // disagree crosses a kink (a point switching between loading and unloading, or reaching onset)
  // and has no derivative to compare with; those are counted and left out.
  const double step = 1e-9;
  double worst = 0.0, scale = k.cwiseAbs().maxCoeff();
  int checked = 0, kinked = 0;
  for (int col = 0; col < g.dofs.unknowns(); col += 3) {
    const auto c0 = g.dofs.component[static_cast<std::size_t>(col)];
    Eigen::VectorXd plus = du, minus = du;
    plus[c0] += step;
    minus[c0] -= step;
    Trial tp, tm;
    evaluateTrial(solver.setup(), p, g, plus, false, SnapBackPolicy::Stop, tp);
    evaluateTrial(solver.setup(), p, g, minus, false, SnapBackPolicy::Stop, tm);
    const Eigen::VectorXd forward = (tp.internalForce - base.internalForce) / step;
    const Eigen::VectorXd backward = (base.internalForce - tm.internalForce) / step;
    if ((forward - backward).cwiseAbs().maxCoeff() > 1e-3 * scale) {
      ++kinked;
      continue;
    }
    ++checked;
    for (int row = 0; row < g.dofs.unknowns(); ++row) {
      const auto c = g.dofs.component[static_cast<std::size_t>(row)];
      worst = std::max(worst, std::abs(0.5 * (forward[c] + backward[c]) - k(row, col)));
    }
  }
  std::printf("loading %d, unloading %d; tangent: %d columns checked, %d across a kink, worst |K - dF/du| = %.3g (max |K| %.3g)\n", loading, unloading, checked,
              kinked, worst, scale);
  EXPECT_GT(checked, 3 * kinked);
  EXPECT_LT(worst, 1e-5 * scale);
}

}  // namespace
}  // namespace ecm::mpm::test

namespace ecm::mpm::test {
namespace {

// A bar 1000 mm long in uniaxial tension (nu = 0) with one weakened row of cells (f_t' 2.9 MPa
// instead of 3): it cracks there and unloads elsewhere, so the top moves
// delta = sigma L / E + w(sigma), w the band's opening of the closed form
// (material/uniaxial_closed_form.hpp), H = the cell size (10 mm). L > h (E + E_p)/E_p = 195.6 mm:
// past the peak delta decreases (a structural snap-back), and displacement control of the top
// cannot follow. Indirect control on the opening across the weak row traces it.
constexpr double kBarLength = 1000.0, kBarWeakFt = 2.9;

Scene snapBackBar(ShapeFunction shape = ShapeFunction::Linear) {
  Scene s;
  s.solver.shapeFunction = shape;
  s.name = "snap-back-bar";
  s.grid = {Vec2(-10.0, -10.0), Vec2(10.0, 10.0), 4, 102};
  s.materials = concreteWithWeakRow(kBarWeakFt);
  s.bodies = {{Shape::rectangle(Vec2(0.0, 0.0), Vec2(20.0, kBarLength)), 0, false, Vec2::Zero()},
              {Shape::rectangle(Vec2(-1.0, 490.0), Vec2(21.0, 500.0)), 1, false, Vec2::Zero()}};
  s.conditions = {NodeCondition::fixed("base", {Vec2(-1.0, 0.0), Vec2(21.0, 0.0)}, false, true),
                  NodeCondition::fixed("corner", {Vec2(-1.0, -1.0), Vec2(0.0, 0.0)}, true, false)};
  NodeCondition top;
  top.name = "top";
  top.box = {Vec2(-1.0, kBarLength), Vec2(21.0, kBarLength)};
  top.component[1] = {Prescribed::Displacement, TimeFunction::hold(0.0)};  // driven by the load factor
  s.conditions.push_back(top);
  s.endTime = 1.0;
  return s;
}

// Indirect control of the snap-back bar: the top moves by the load factor (mm), the step is set
// by the opening across the weak row (the mean u_y at y = 500 minus at y = 490).
IndirectControl weakRowOpening(const Grid& g) {
  IndirectControl control;
  control.driven = {2};
  control.reference = Vec2(0.0, 1.0);
  for (int i = 0; i <= 2; ++i) {
    control.terms.push_back({2 * g.node(i + 1, 51) + 1, 1.0 / 3.0});
    control.terms.push_back({2 * g.node(i + 1, 50) + 1, -1.0 / 3.0});
  }
  return control;
}

// Linear and uGIMP shape functions (quadratic B-splines are refused in implicit scenes: no
// boundary treatment). The bar's grid has a free margin of nodes: uGIMP particles at the body's
// edge reach the margin nodes with weight and gradient exactly 0, which must not become unknowns.
class ImplicitBar : public ::testing::TestWithParam<ShapeFunction> {};

// The same bar under displacement control of its top, 0.01 mm of pseudo-time per step to
// 0.12 mm: past the peak (delta 0.0906 mm) no equilibrium near the last one has the prescribed
// displacement, and the step is stabilised (docs/implicit.md, "Stabilised steps"): its proximal
// steps walk the bar down to the closed form's branch after the snap-back, at the same delta, as a
// dynamic test would jump. Expected values from the closed form (bar_closed_form.hpp): every
// row on the curve, the rows after the jump on its branch past the least delta, and the energy the
// dashpots took equal to the area of the loop the jump cuts off, the external work of the jump
// less the work along the curve from the state before it, over the peak and the snap-back, to the
// state after it (0.62 N mm).
TEST(ImplicitBarJump, DisplacementControlJumpsTheSnapBackInAStabilisedStep) {
  const DamageLawParams law{32000.0, kBarWeakFt, ecm::test::kEp, ecm::test::kN};
  const BarClosedForm exact(law, kBarLength, ecm::test::kBandWidth, 1e-4);
  Scene scene = snapBackBar();
  scene.conditions[2].component[1] = {Prescribed::Displacement, TimeFunction::linearRamp(0.12, 1.0)};
  ImplicitSettings settings;
  settings.loadStep = 0.01;
  settings.maxHalvings = 4;
  ASSERT_GT(settings.stabilization, 0.0);  // on by default
  scene.solver.implicit = settings;
  ImplicitSolver solver(scene);
  const double area = 20.0 * scene.thickness;
  std::vector<std::pair<double, double>> rows;  // (delta, F)
  int stabilized = 0;
  double worst = 0.0, dashpots = 0.0, before = 0.0, after = 0.0, fBefore = 0.0, fAfter = 0.0;
  while (solver.time() < 1.0 - 1e-12) {
    const double d0 = solver.conditions()[2].displacement[1], f0 = solver.conditions()[2].reaction[1];
    const ImplicitStepReport r = solver.advance(settings.loadStep, 1.0 - solver.time());
    const double delta = solver.conditions()[2].displacement[1], force = solver.conditions()[2].reaction[1];
    worst = std::max(worst, exact.distance(delta, force / area));
    if (r.proximalSteps > 0) ++stabilized, dashpots += r.dashpotWork, before = d0, fBefore = f0, after = delta, fAfter = force;
  }
  ASSERT_EQ(stabilized, 1);
  EXPECT_NEAR(solver.energies().damping, dashpots, 1e-12);
  // The closed form's loop: along the curve from delta `before` on the rising branch, over the
  // peak and down the snap-back, to delta `after` on the branch past the least delta.
  const std::vector<double>& d = exact.delta;
  const std::vector<double>& s = exact.sigma;
  const auto top = static_cast<std::size_t>(std::max_element(s.begin(), s.end()) - s.begin());
  const auto least = static_cast<std::size_t>(std::min_element(d.begin() + static_cast<std::ptrdiff_t>(top), d.end()) - d.begin());
  // (The curve starts at the peak: the rising branch before it is the straight line F = E A delta / L.)
  double along = 0.5 * (fBefore + s[top] * area) * (d[top] - before);
  std::size_t k = top;
  for (; k + 1 < d.size() && (k < least || d[k + 1] < after); ++k) along += 0.5 * (s[k] + s[k + 1]) * area * (d[k + 1] - d[k]);
  ASSERT_LT(k + 1, d.size());
  const double last = s[k] + (after - d[k]) / (d[k + 1] - d[k]) * (s[k + 1] - s[k]);  // sigma at `after`
  along += 0.5 * (s[k] + last) * area * (after - d[k]);
  const double loop = 0.5 * (fBefore + fAfter) * (after - before) - along;
  std::printf("[ bar jump ] before %.5f mm, %.3f N; after %.5f mm, %.3f N; dashpots %.5f N mm, the closed form's loop %.5f N mm; "
              "worst distance to the curve %.2e\n", before, fBefore, after, fAfter, dashpots, loop, worst);
  EXPECT_GT(fBefore, 0.99 * kBarWeakFt * area);  // it jumps from the peak ...
  EXPECT_LT(fAfter, 0.1 * kBarWeakFt * area);    // ... to the branch past the snap-back
  EXPECT_LT(worst, 1e-3);
  EXPECT_NEAR(dashpots, loop, 1e-3 * loop);  // 1e-5 measured
}

TEST_P(ImplicitBar, IndirectControlTracesTheBarsStructuralSnapBack) {
  const DamageLawParams law{32000.0, kBarWeakFt, ecm::test::kEp, ecm::test::kN};
  ImplicitSolver solver(snapBackBar(GetParam()));
  const Grid& g = solver.setup().scene.grid;
  const IndirectControl control = weakRowOpening(g);  // the top moves lambda mm
  const BarClosedForm exact(law, kBarLength, ecm::test::kBandWidth, 1e-3);
  const double d0 = exact.d0;
  double worst = 0.0, peakDelta = 0.0, peakSigma = 0.0, deltaAfterPeak = INFINITY;
  int iterations = 0;
  // Steps of the opening: 1e-5 mm to past the peak (an elastic step of it moves the stress by
  // 0.03 MPa: a larger one would carry the strong rows past their onset at 3 MPa in the trial,
  // and Newton may then find the equilibrium where every row cracks), then 1e-4 mm.
  const int steps = 700;
  for (int k = 0; k < steps; ++k) {
    const ImplicitStepReport r = solver.step(control, k < 150 ? 1e-5 : 1e-4);  // mm of opening
    iterations += r.totalIterations;
    const double delta = solver.conditions()[2].displacement[1];
    const double sigma = solver.conditions()[2].reaction[1] / (20.0 * solver.setup().scene.thickness);
    worst = std::max(worst, exact.distance(delta, sigma));
    if (sigma > peakSigma) peakSigma = sigma, peakDelta = delta;
    if (sigma < peakSigma) deltaAfterPeak = std::min(deltaAfterPeak, delta);
  }
  std::printf("[ snap-back bar, %s ] peak %.4f MPa at delta %.5f mm, delta falls to %.5f mm after it; worst distance to "
              "the closed form %.2e; %d Newton iterations in %d steps; load factor %.5f\n",
              toString(GetParam()), peakSigma, peakDelta, deltaAfterPeak, worst, iterations, steps, solver.loadFactor());
  EXPECT_NEAR(peakSigma, kBarWeakFt, 1e-3 * kBarWeakFt);
  // Traced through the snap-back: past the peak delta falls to the closed form's least value.
  const auto top = std::max_element(exact.sigma.begin(), exact.sigma.end()) - exact.sigma.begin();
  const double cfPeak = exact.delta[static_cast<std::size_t>(top)];
  const double cfLeast = *std::min_element(exact.delta.begin() + top, exact.delta.end());
  std::printf("[ snap-back bar ] closed form: peak at delta %.5f mm, least delta after it %.5f mm\n", cfPeak, cfLeast);
  EXPECT_LT(cfLeast, cfPeak - 0.01 * d0);  // the closed form does snap back
  EXPECT_NEAR(deltaAfterPeak, cfLeast, 1e-3 * d0);
  EXPECT_LT(worst, 1e-3);
  const Particles& p = solver.particles();
  for (std::size_t i = 0; i < p.size(); ++i)
    if (p.band[i] >= 0) {
      EXPECT_EQ(p.material[i], 1) << "only the weak row cracks";
    }
}
// uGIMP: the top particles' domains move past the driven node row into the margin cells at once;
// the margin nodes they reach carry a share of 1e-5 of a cell and are tied to the rows below
// (mpm/implicit/node_ties.hpp). Left free, they unloaded the top row, and the row below cracked at
// half the bar's strength (30 N instead of 58 N).
INSTANTIATE_TEST_SUITE_P(ShapeFunctions, ImplicitBar, ::testing::Values(ShapeFunction::Linear, ShapeFunction::UGimp),
                         [](const auto& info) { return std::string(toString(info.param)); });

// The AMG solver (linear_solver: amg; docs/implicit.md, "The AMG solver") solves each step's
// systems to a relative residual of 1e-3 (ImplicitSettings::krylovTolerance), where the LU is
// exact to round-off; Newton then converges to the same equilibria within its own tolerance (1e-6
// of the forces). Expected: the bar's stress history through its snap-back equal to the LU's
// within 1e-6 f_t' (1.8e-6 MPa measured), and so on the closed form (to 1e-3 f_t', as above).
TEST(ImplicitAmg, TracesTheBarsSnapBackAsTheLUDoes) {
  if (!available(LinearSolverKind::Amg)) GTEST_SKIP() << "this build has no hypre (libhypre-dev)";
  const DamageLawParams law{32000.0, kBarWeakFt, ecm::test::kEp, ecm::test::kN};
  const BarClosedForm exact(law, kBarLength, ecm::test::kBandWidth, 1e-3);
  const auto run = [&](LinearSolverKind kind) {
    Scene scene = snapBackBar(ShapeFunction::Linear);
    ImplicitSettings settings = scene.solver.implicit.value_or(ImplicitSettings{});
    settings.linearSolver = kind;
    scene.solver.implicit = settings;
    ImplicitSolver solver(scene);
    const Grid& g = solver.setup().scene.grid;
    const IndirectControl control = weakRowOpening(g);
    std::vector<double> sigma;
    EXPECT_EQ(solver.linearSolver().amgStatistics() != nullptr, false);  // none before the first step
    for (int k = 0; k < 400; ++k) {
      solver.step(control, k < 150 ? 1e-5 : 1e-4);
      const double delta = solver.conditions()[2].displacement[1];
      sigma.push_back(solver.conditions()[2].reaction[1] / (20.0 * solver.setup().scene.thickness));
      EXPECT_LT(exact.distance(delta, sigma.back()), 1e-3) << toString(kind) << ", step " << k;
    }
    EXPECT_EQ(solver.linearSolver().amgStatistics() != nullptr, kind == LinearSolverKind::Amg) << "the solver asked for";
    return sigma;
  };
  const std::vector<double> lu = run(defaultLinearSolver()), amg = run(LinearSolverKind::Amg);
  double worst = 0.0;
  for (std::size_t k = 0; k < lu.size(); ++k) worst = std::max(worst, std::abs(amg[k] - lu[k]));
  std::printf("[ snap-back bar, amg ] largest stress difference to the LU %.2e MPa; peak %.4f MPa\n", worst,
              *std::max_element(amg.begin(), amg.end()));
  EXPECT_LT(worst, 1e-6 * kBarWeakFt);
  EXPECT_NEAR(*std::max_element(amg.begin(), amg.end()), kBarWeakFt, 1e-3 * kBarWeakFt);
}

#ifdef ECM_HAVE_HYPRE
// Every option of the AMG solver (AmgOptions; docs/implicit.md, "Its memory and its options")
// solves the DEN coarse tangent to its tolerance: the residual |b - K x| <= 1e-8 |b| computed here,
// not taken from hypre, and x equal to a sparse LU's to 1e-6 (K's condition leaves the
// difference 1e-8 times it). The options reach hypre (Debian 12's 2.26): aggressive coarsening
// doubles the iterations (10 -> 19), an l1-Jacobi smoother adds 3, and without ILU(0) on the
// finest level it takes 11 (bench_implicit's BM_AmgSolve: the same counts).
TEST(ImplicitAmg, EveryOptionSolvesTheDenTangentToItsTolerance) {
  const Scene scene = loadSceneFile(std::filesystem::path(ECM_SOURCE_DIR) / "data/den/den-4b-coarse-implicit.yaml");
  ImplicitSolver solver(scene, 1);
  std::vector<int> components;
  const Eigen::SparseMatrix<double> k = solver.tangentAtStart(0.001, &components);
  ASSERT_GT(k.rows(), 10000);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(k.rows(), -1.0, 2.0);
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu(k);
  const Eigen::VectorXd exact = lu.solve(b);
  std::vector<int> iterations;
  for (int v = 0; v < 6; ++v) {
    AmgSolver amg;
    if (v == 1) amg.options.strongThreshold = 0.25;
    if (v == 2) amg.options.aggressiveLevels = 1;
    if (v == 3) amg.options.relaxType = 8;
    if (v == 4) amg.options.relaxType = 18, amg.options.sweeps = 2;
    if (v == 5) amg.options.iluLevels = 0;
    amg.setComponents(components);
    amg.setMatrix(k);
    Eigen::VectorXd x;
    ASSERT_TRUE(amg.solve(b, x)) << "options " << v;
    EXPECT_LE((b - k * x).norm(), 1e-8 * b.norm() * (1.0 + 1e-6)) << "options " << v;
    EXPECT_LE((x - exact).norm(), 1e-6 * exact.norm()) << "options " << v;
    iterations.push_back(amg.lastIterations());
  }
  std::printf("[ amg options ] GMRES iterations: default %d, threshold 0.25 %d, aggressive %d, l1-GS %d, l1-Jacobi %d, "
              "no ILU %d\n", iterations[0], iterations[1], iterations[2], iterations[3], iterations[4], iterations[5]);
  EXPECT_GE(iterations[2], iterations[0] + 5);
  EXPECT_GT(iterations[4], iterations[0]);
  EXPECT_NE(iterations[5], iterations[0]);
}

// The AMG solver's GMRES solves to ImplicitSettings::krylovTolerance (an inexact Newton,
// docs/implicit.md, "Krylov on the kept factorisation"): through the snap-back bar's peak, 1e-3
// takes fewer GMRES iterations than 1e-8, and both stay on the closed form (1e-3 f_t').
TEST(ImplicitAmg, SolvesToTheKrylovToleranceOfTheSettings) {
  const DamageLawParams law{32000.0, kBarWeakFt, ecm::test::kEp, ecm::test::kN};
  const BarClosedForm exact(law, kBarLength, ecm::test::kBandWidth, 1e-3);
  long iterations[2] = {0, 0};
  for (const int loose : {0, 1}) {
    Scene scene = snapBackBar();
    scene.solver.implicit = ImplicitSettings{};
    scene.solver.implicit->linearSolver = LinearSolverKind::Amg;
    scene.solver.implicit->krylovTolerance = loose ? 1e-3 : 1e-8;
    ImplicitSolver solver(scene, 1);
    const IndirectControl control = weakRowOpening(solver.setup().scene.grid);
    for (int k = 0; k < 200; ++k) {
      solver.step(control, 1e-5);
      const double sigma = solver.conditions()[2].reaction[1] / (20.0 * scene.thickness);
      ASSERT_LT(exact.distance(solver.conditions()[2].displacement[1], sigma), 1e-3) << "tolerance " << scene.solver.implicit->krylovTolerance;
    }
    iterations[loose] = solver.linearSolver().amgStatistics()->iterations;
  }
  std::printf("[ amg tolerance ] GMRES iterations through the bar's peak: %ld at 1e-8, %ld at 1e-3\n", iterations[0], iterations[1]);
  EXPECT_LT(iterations[1], iterations[0]);
}
#endif

// The extrapolated start (docs/implicit.md) changes where Newton begins, not what it converges
// to: on the bar through its snap-back both starts stay on the closed form (to 1e-3 of f_t', the
// check above), and the extrapolated one needs fewer Newton iterations.
TEST(Implicit, TheExtrapolatedStartSavesIterationsOnTheSameCurve) {
  const DamageLawParams law{32000.0, kBarWeakFt, ecm::test::kEp, ecm::test::kN};
  const BarClosedForm exact(law, kBarLength, ecm::test::kBandWidth, 1e-3);
  int iterations[2] = {0, 0};
  for (const bool extrapolate : {false, true}) {
    Scene scene = snapBackBar();
    if (!scene.solver.implicit) scene.solver.implicit = ImplicitSettings{};
    scene.solver.implicit->extrapolate = extrapolate;
    ImplicitSolver solver(scene, 1);
    const Grid& g = solver.setup().scene.grid;
    const IndirectControl control = weakRowOpening(g);
    double worst = 0.0;
    for (int k = 0; k < 300; ++k) {  // through the peak and the snap-back (the test above: 150 small steps, then larger)
      iterations[extrapolate] += solver.step(control, k < 150 ? 1e-5 : 1e-4).totalIterations;
      const double delta = solver.conditions()[2].displacement[1];
      const double sigma = solver.conditions()[2].reaction[1] / (20.0 * solver.setup().scene.thickness);
      worst = std::max(worst, exact.distance(delta, sigma));
    }
    EXPECT_LT(worst, 1e-3) << "extrapolate " << extrapolate;
  }
  std::printf("[ extrapolated start ] Newton iterations: %d from du = 0, %d extrapolated\n", iterations[0], iterations[1]);
  EXPECT_LT(iterations[1], iterations[0]);
}


// Krylov on the kept factorisation (docs/implicit.md): each Newton step is the current tangent's,
// by GMRES preconditioned with the kept LU, instead of the kept LU's own (modified Newton, which
// refactorises where the residual falls by less than 10 per iteration). Expected: the same
// curves (on the closed form to 1e-3 f_t', as above), no more factorisations nor Newton
// iterations (fewer of both where the tangent softens: 11 -> 2 and 1,534 -> 1,102 on the short
// bar), and Krylov vectors used. Both of Newton's systems: the bordered one of indirect control (the snap-back bar) and
// the plain one of displacement control (a bar of 150 mm, shorter than h (E + E_p) / E_p = 195.6 mm:
// no snap-back, so displacement control follows the softening).
TEST(Implicit, KrylovOnTheKeptFactorisationStaysOnTheBarsCurveWithFewerFactorisations) {
  const DamageLawParams law{32000.0, kBarWeakFt, ecm::test::kEp, ecm::test::kN};
  const double shortLength = 150.0;
  const BarClosedForm snapBack(law, kBarLength, ecm::test::kBandWidth, 1e-3), shortBar(law, shortLength, ecm::test::kBandWidth, 1e-3);
  long factorizations[2][2] = {{0, 0}, {0, 0}}, krylov[2][2] = {{0, 0}, {0, 0}}, newton[2][2] = {{0, 0}, {0, 0}};
  for (const int vectors : {0, 8}) {
    const int on = vectors > 0 ? 1 : 0;
    {  // indirect control through the snap-back
      Scene scene = snapBackBar();
      scene.solver.implicit = ImplicitSettings{};
      scene.solver.implicit->krylovIterations = vectors;
      ImplicitSolver solver(scene, 1);
      const Grid& g = solver.setup().scene.grid;
      const IndirectControl control = weakRowOpening(g);
      double worst = 0.0;
      for (int k = 0; k < 300; ++k) {
        const ImplicitStepReport r = solver.step(control, k < 150 ? 1e-5 : 1e-4);
        factorizations[0][on] += r.factorizations, krylov[0][on] += r.krylovIterations, newton[0][on] += r.totalIterations;
        const double delta = solver.conditions()[2].displacement[1];
        worst = std::max(worst, snapBack.distance(delta, solver.conditions()[2].reaction[1] / (20.0 * scene.thickness)));
      }
      EXPECT_LT(worst, 1e-3) << "indirect, Krylov vectors " << vectors;
    }
    {  // displacement control of the short bar's top, 0.1 mm over 400 steps
      Scene scene = snapBackBar();
      scene.grid = {Vec2(-10.0, -10.0), Vec2(10.0, 10.0), 4, 17};
      scene.bodies[0].shape = Shape::rectangle(Vec2(0.0, 0.0), Vec2(20.0, shortLength));
      scene.bodies[1].shape = Shape::rectangle(Vec2(-1.0, 70.0), Vec2(21.0, 80.0));
      scene.conditions[2].box = {Vec2(-1.0, shortLength), Vec2(21.0, shortLength)};
      scene.conditions[2].component[1] = {Prescribed::Displacement, TimeFunction::linearRamp(0.1, 1.0)};
      scene.solver.implicit = ImplicitSettings{};
      scene.solver.implicit->krylovIterations = vectors;
      ImplicitSolver solver(scene, 1);
      double worst = 0.0, peak = 0.0, last = 0.0;
      for (int k = 0; k < 400; ++k) {
        const ImplicitStepReport r = solver.step(1.0 / 400);
        factorizations[1][on] += r.factorizations, krylov[1][on] += r.krylovIterations, newton[1][on] += r.totalIterations;
        last = solver.conditions()[2].reaction[1] / (20.0 * scene.thickness);
        peak = std::max(peak, last);
        worst = std::max(worst, shortBar.distance(solver.conditions()[2].displacement[1], last));
      }
      EXPECT_LT(worst, 1e-3) << "displacement control, Krylov vectors " << vectors;
      EXPECT_LT(last, 0.5 * peak) << "the band has softened";
    }
  }
  for (int path = 0; path < 2; ++path)
    std::printf("[ krylov on the kept LU ] %s: factorisations %ld -> %ld, Newton iterations %ld -> %ld, Krylov vectors %ld\n",
                path == 0 ? "indirect" : "displacement", factorizations[path][0], factorizations[path][1], newton[path][0],
                newton[path][1], krylov[path][1]);
  // (On the snap-back bar the one cracked row hardly changes the tangent: the kept LU serves
  // either way, one factorisation each, and the Krylov vectors converge at once.)
  EXPECT_LT(factorizations[1][1], factorizations[1][0]);
  EXPECT_LT(newton[1][1], newton[1][0]);
  for (int path = 0; path < 2; ++path) {
    EXPECT_LE(factorizations[path][1], factorizations[path][0]) << "path " << path;
    EXPECT_LE(newton[path][1], newton[path][0]) << "path " << path;
    EXPECT_EQ(krylov[path][0], 0) << "path " << path;
    EXPECT_GT(krylov[path][1], 0) << "path " << path;
  }
}

}  // namespace
}  // namespace ecm::mpm::test
