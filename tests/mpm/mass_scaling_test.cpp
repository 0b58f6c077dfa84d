// Nodes with little mass (docs/model.md, "Nodes with little mass"): a node that a particle has
// only just reached carries a sliver of its mass but the full gradient of its linear shape
// function, so its own frequency sqrt(k / m) outruns the explicit step. The grid update gives such
// a node (below 0.2 of a full node's mass; USL, linear shape functions) 0.2 of a full node's mass
// for its acceleration; no inner, edge or corner node of a body is touched, so runs without such
// nodes are bitwise unchanged.
#include <gtest/gtest.h>

#include <cmath>

#include "mpm/explicit/explicit_solver.hpp"
#include "test_scenes.hpp"

namespace ecm::mpm::test {
namespace {

// A 20 x 20 mm elastic block (E 1000 MPa, rho 1e-9: c = 1e6 mm/s) in a grid with 5 mm of room
// above it, stretched along y and moving up with v0: its top particles cross into the empty row
// of cells above it.
Scene risingBlock(ShapeFunction shape, int ppc, double v0, double cfl = 0.6) {
  Scene s;
  s.name = "rising-block";
  s.grid = {Vec2(-3.0, -3.0), Vec2(1.0, 1.0), 26, 31};
  s.materials = {elasticMaterial(1000.0, 0.2, 1e-9)};
  s.bodies = {{Shape::rectangle(Vec2(0.0, 0.0), Vec2(20.0, 20.0)), 0, false, Vec2(0.0, v0)}};
  s.particlesPerCell = ppc;
  s.solver.shapeFunction = shape;
  s.solver.explicitScheme.cfl = cfl;
  s.endTime = 1.0;
  return s;
}

// The block's particles stretched by 1e-4 along y (sigma_yy about 0.1 MPa) and spread in y by
// the same, so that the rise starts from a stressed state.
void prestress(ExplicitSolver& solver) {
  Particles& p = solver.editParticles();
  for (std::size_t i = 0; i < p.size(); ++i) {
    p.strain[i] = Voigt(0.0, 1e-4, 0.0);
    MaterialPoint point;
    point.strain = p.strain[i];
    p.stress[i] = solver.materials()[0].stress(point);
  }
}

double kineticEnergy(const ExplicitSolver& s) {
  const Particles& p = s.particles();
  double e = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) e += 0.5 * p.mass[i] * p.velocity[i].squaredNorm();
  return e;
}

// A body at rest in its grid, inner, edge and corner nodes only: no node is scaled, for 1 to 4
// particles per cell, at CFL 0.6 and 0.9 (linear shape functions; uGIMP and B-splines never scale:
// their weights and gradients fade together at the edge of their support).
TEST(MassScaling, NoFullOrSurfaceNodeIsEverScaled) {
  for (const double cfl : {0.6, 0.9})
  for (const ShapeFunction shape : {ShapeFunction::Linear, ShapeFunction::UGimp, ShapeFunction::BSpline2})
    for (int ppc = 1; ppc <= 4; ++ppc) {
      ExplicitSolver solver(risingBlock(shape, ppc, 0.0, cfl), 1);
      prestress(solver);
      for (int k = 0; k < 5; ++k) solver.advance();
      EXPECT_EQ(solver.massScaled(), 0) << "shape " << static_cast<int>(shape) << ", " << ppc << " particles per cell, cfl " << cfl;
    }
}

// The rising block with linear shape functions, unstressed, moving up at v0 = 500 mm/s: its top
// row of particles (0.25 mm below y = 20, two per cell) crosses y = 20 at step 851, and the nodes
// on y = 21 take a sliver of mass. Without the raised mass the block, which only translates,
// blew up within 10 steps of the crossing (a particle out of the grid at step 860; with 0.1 of
// a full node's mass at step 1413). With it the kinetic energy stays 1/2 M v0^2 to 1e-4 through
// the crossing of two rows of cells.
TEST(MassScaling, ParticlesEnteringEmptyCellsDoNotShakeTheirNodesApart) {
  const double v0 = 500.0;
  ExplicitSolver solver(risingBlock(ShapeFunction::Linear, 2, v0), 1);
  const double own = 0.5 * 20.0 * 20.0 * 1.0 * 1e-9 * v0 * v0;  // N mm: 1 mm thick
  double top = 0.0;
  for (int k = 0; k < 6000; ++k) {
    solver.advance();
    if (k % 500 == 0) {
      EXPECT_NEAR(kineticEnergy(solver), own, 1e-4 * own) << "step " << k;
    }
  }
  const Particles& p = solver.particles();
  for (std::size_t i = 0; i < p.size(); ++i) top = std::max(top, p.position[i][1]);
  EXPECT_GT(top, 21.5) << "the top row crossed y = 20 and y = 21";
  EXPECT_GT(solver.massScaled(), 0);
}

}  // namespace
}  // namespace ecm::mpm::test
