#pragma once
// Small scenes shared by the MPM tests (units: mm, N, MPa, t, s).
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "../paper_constants.hpp"
#include "mpm/explicit/explicit_solver.hpp"

namespace ecm::mpm::test {

inline MaterialParams elasticMaterial(double e = 32000.0, double nu = 0.0, double density = 2.4e-9,
                                      Hypothesis h = Hypothesis::PlaneStress) {
  MaterialParams m{.name = "elastic", .model = ModelKind::LinearElastic, .elastic = {e, nu, h}, .density = density};
  return m;
}

// The paper's DEN concrete (tests/paper_constants.hpp) with a density.
inline MaterialParams paperConcrete() {
  MaterialParams m{.name = "den-concrete", .model = ModelKind::Enriched,
                   .elastic = {ecm::test::kE, ecm::test::kNu, Hypothesis::PlaneStress}, .density = 2.4e-9,
                   .tensileStrength = ecm::test::kFt, .softeningModulus = ecm::test::kEp,
                   .softeningExponent = ecm::test::kN, .bandWidth = ecm::test::kBandWidth};
  return m;
}

// A free-free bar of length L along x, one cell high, `cells` cells long, with a margin of
// two cells on every side; nu = 0 makes it one-dimensional.
struct BarSetup {
  double length = 100.0;   // mm
  double e = 32000.0;      // MPa
  double density = 2.4e-9; // t/mm^3
  int cells = 64;
  ShapeFunction shape = ShapeFunction::Linear;
  UpdateScheme scheme = UpdateScheme::USL;
  double cfl = 0.3;

  double h() const { return length / cells; }
  double x0() const { return 2.0 * h(); }
  double waveSpeed() const { return std::sqrt(e / density); }
  double omega() const { return std::numbers::pi * waveSpeed() / length; }  // mode 1, free-free
  double period() const { return 2.0 * length / waveSpeed(); }
  double v0() const { return 1e-4 * waveSpeed(); }  // peak strain 1e-4
  double mode(double x) const { return std::cos(std::numbers::pi * (x - x0()) / length); }

  Scene scene() const {
    Scene s;
    s.name = "bar";
    s.grid = {Vec2::Zero(), Vec2(h(), h()), cells + 4, 5};
    s.materials = {elasticMaterial(e, 0.0, density)};
    s.bodies = {{Shape::rectangle(Vec2(x0(), 2.0 * h()), Vec2(x0() + length, 3.0 * h())), 0, false, Vec2::Zero()}};
    s.particlesPerCell = 2;
    s.solver.shapeFunction = shape;
    s.solver.explicitScheme.scheme = scheme;
    s.solver.explicitScheme.cfl = cfl;
    return s;
  }
  // v(X, 0) = v0 cos(pi (X - x0) / L): mode 1, u(X, t) = v0 / omega cos(...) sin(omega t).
  void setInitialVelocity(ExplicitSolver& solver) const {
    auto& p = solver.editParticles();
    for (std::size_t i = 0; i < p.size(); ++i) p.velocity[i] = Vec2(v0() * mode(p.position[i][0]), 0.0);
  }
};

}  // namespace ecm::mpm::test

namespace ecm::mpm::test {

// A 100 x 100 mm block on a fixed base, pulled at its top row of particles by a total force
// (smooth ramp, then held), with local damping: a quasi-static elastic run.
// A 10 x 10 mm elastic block (E 1000 MPa, nu 0, 1 mm thick; 2 x 2 particles per 10 mm cell, at 2.5
// and 7.5 mm) on a base held in y, its top pulled 0.01 mm in 1 s: a uniform strain of 1e-3 and a
// top reaction of 10 N. A scene's YAML, to append a solver or gauges to. Units: mm, N, MPa, t, s.
inline std::string pulledBlockYaml(const std::string& name) {
  return "name: " + name + R"(
grid: {origin: [-10, -10], cell_size: [10, 10], cells: [3, 3]}
thickness: 1
particles_per_cell: 2
materials:
  - {name: e, model: linear_elastic, hypothesis: plane_stress, youngs_modulus: 1000, poisson_ratio: 0.0, density: 1e-9}
bodies:
  - {rectangle: {min: [0, 0], max: [10, 10]}, material: e}
end_time: 1
conditions:
  - {name: base, box: {min: [-1, 0], max: [11, 0]}, fixed: [y]}
  - {name: corner, box: {min: [-1, -1], max: [0, 0]}, fixed: [x]}
  - {name: top, box: {min: [-1, 10], max: [11, 10]}, displacement: {y: {type: linear_ramp, value: 0.01, time: 1}}}
)";
}

// The paper's concrete with nu = 0 (a one-dimensional bar or block) and a copy named "weak"
// with the tensile strength weakFt (MPa), where the crack is to open: materials 0 and 1.
inline std::vector<MaterialParams> concreteWithWeakRow(double weakFt) {
  MaterialParams strong = paperConcrete();
  strong.elastic.poissonRatio = 0.0;
  MaterialParams weak = strong;
  weak.name = "weak";
  weak.tensileStrength = weakFt;
  return {strong, weak};
}

inline Scene tensionBlock(double force = 1000.0, int cells = 10) {
  const double h = 100.0 / cells;
  Scene s;
  s.name = "tension-block";
  s.grid = {Vec2::Zero(), Vec2(h, h), cells, cells + 2};
  s.materials = {elasticMaterial(32000.0, 0.0)};
  s.bodies = {{Shape::rectangle(Vec2(0.0, 0.0), Vec2(100.0, 100.0)), 0, false, Vec2::Zero()}};
  s.conditions = {NodeCondition::fixed("base", {Vec2(-1.0, 0.0), Vec2(101.0, 0.0)})};
  s.loads = {{"pull", {Vec2(-1.0, 100.0 - h / 2.0), Vec2(101.0, 101.0)}, LoadTarget::Particles, Vec2(0.0, force),
              TimeFunction::smoothRamp(1.0, 3e-4)}};
  s.solver.explicitScheme.damping.local = 0.3;
  // The paper's rule: these blocks crack wherever their points reach onset (the times and counts
  // the tests below rely on were taken with it; tracked paths have tests of their own).
  s.solver.crackPath = CrackPathRule::Free;
  s.endTime = 1.2e-3;
  return s;
}

// The tension block of 5 mm cells in the paper's concrete with a notch on the left, pulled at
// the top by a velocity ramp (150 mm/s): it cracks within ~200 steps (threads, checkpoints).
inline Scene notchedCrackingBlock() {
  Scene s = tensionBlock(0.0, 20);
  s.loads.clear();
  s.materials = {paperConcrete()};
  s.bodies.push_back({Shape::polygon({Vec2(-1.0, 45.0), Vec2(20.0, 49.0), Vec2(20.0, 51.0), Vec2(-1.0, 55.0)}), 0, true,
                      Vec2::Zero()});
  s.grid = {Vec2(-10.0, -10.0), Vec2(5.0, 5.0), 24, 26};
  s.conditions = {NodeCondition::fixed("base", {Vec2(-20.0, 0.0), Vec2(120.0, 0.0)})};
  NodeCondition top;
  top.name = "top";
  top.box = {Vec2(-20.0, 100.0), Vec2(120.0, 100.0)};
  top.component[1] = {Prescribed::Velocity, TimeFunction::smoothRamp(150.0, 2e-5)};
  s.conditions.push_back(top);
  s.solver.explicitScheme.damping.local = 0.1;
  return s;
}

// The notched cracking block with the second-band option, also pulled sideways at its right
// edge: the bulk along the notch's horizontal crack goes into tension and second bands open
// (docs/model.md, "A second band"). 1560 particles; the first second bands open by ~1.3e-4 s.
inline Scene twoBandBlock() {
  Scene s = notchedCrackingBlock();
  s.name = "two-band-block";
  s.materials[0].secondBand = SecondBandOption::Orthogonal;
  NodeCondition right;
  right.name = "right";
  right.box = {Vec2(100.0, 5.0), Vec2(100.0, 95.0)};
  right.component[0] = {Prescribed::Velocity, TimeFunction::smoothRamp(150.0, 2e-5)};
  s.conditions.push_back(right);
  s.endTime = 2.4e-4;
  s.outputInterval = 2e-5;
  return s;
}

}  // namespace ecm::mpm::test
