// One explicit MPM step, as the textbook writes it: for each update scheme the phases in order,
//   P2G   particleToGrid   mass, momentum and forces from the particles to the nodes
//   grid  updateGrid       v = p / m, f -> v^{n+1} with damping, the node conditions and reactions
//   G2P   gridToParticle   velocities (PIC/FLIP) and positions back to the particles
//   strain computeStrainIncrements / gridToParticle(true)   d eps = dt sym grad v at the particle
//   stress updateStresses  Material::update of every particle (material/material.hpp)
// Each phase is a Solver member over the plain state: particles_ (mpm/particles.hpp), grid_
// (mpm/grid.hpp), conditions_ and loads_. The phases live in transfer.cpp (P2G, G2P, strain),
// grid_update.cpp and stress_update.cpp.
//
// USL, the default, runs the same phases fused into one pass over the particles
// (fused_transfer.cpp): each particle gathers from the updated grid (G2P), takes its strain
// increment and, where it has one, its closed-form stress, and scatters its mass, momentum and
// force into the next step's grid (the next step's P2G) while its fields are in cache. The
// particles without a closed form (cracked, near onset, smeared) are deferred: they take
// Material::update after the pass and scatter then. The fused pass therefore leaves the next
// step's P2G done: the grid "holds the state" (gridHoldsState_) and the next step starts at the
// grid phase. Only this file sets that flag; anything that changes the particles between steps
// (a restart, editParticles(), phases run by hand) calls rebuildGridNextStep(), and the next
// step rebuilds that scatter first (scatterState).
//
// The fused USL gives the plain sequence's results up to the order of the sums: within a part of
// the particles it adds the closed-form points before the deferred ones (1e-12 relative on the
// DEN; tests/mpm/fused_transfer_test.cpp).
#include "mpm/solver.hpp"

namespace ecm::mpm {

void Solver::advance() {
  if (scene_.solver.scheme == UpdateScheme::USL) {
    if (!gridHoldsState_) scatterState();  // P2G of this step: first step, restart, particles edited
    gridHoldsState_ = false;               // until the pass below has scattered every point anew
    addLoads();
    updateGrid();
    const bool inGrid = gatherStressScatter();  // G2P, strain, closed-form stresses, the next step's P2G
    updateStresses(true);                       // stress of the deferred points
    if (inGrid) {  // (a stencil that left the grid is reported by the next step's scatterState)
      scatterDeferred();  // their share of the next step's P2G
      gridHoldsState_ = true;
    }
  } else {
    phases();
  }
  time_ += dt_;
  ++step_;
}

void Solver::advanceByPhases() {
  phases();
  time_ += dt_;
  ++step_;
}

void Solver::phases() {
  gridHoldsState_ = false;  // the plain phases leave no scatter for the next step
  switch (scene_.solver.scheme) {
    case UpdateScheme::USF:  // update stress first: strain from the step's starting velocities
      particleToGrid(kStencils | kMassMomentum);
      gridVelocities();
      computeStrainIncrements();
      updateStresses();
      particleToGrid(kForces);
      updateGrid();
      gridToParticle(false);
      break;
    case UpdateScheme::USL:  // update stress last: strain from the updated grid velocities
      particleToGrid(kStencils | kMassMomentum | kForces);
      updateGrid();
      gridToParticle(true);
      updateStresses();
      break;
    case UpdateScheme::MUSL:  // modified USL: the grid velocities remapped from the updated particles
      particleToGrid(kStencils | kMassMomentum | kForces);
      updateGrid();
      gridToParticle(false);
      particleToGrid(kMassMomentum);
      gridVelocities();
      computeStrainIncrements();
      updateStresses();
      break;
  }
}

}  // namespace ecm::mpm
