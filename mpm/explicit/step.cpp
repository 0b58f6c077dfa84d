// One explicit MPM step, as the textbook writes it: for each update scheme the phases of
// mpm/explicit/phases.hpp in order, over the plain state of mpm/explicit/state.hpp (particles, grid, conditions,
// loads, the clock and the run's totals):
//   P2G    particleToGrid + addLoads   mass, momentum and forces from the particles to the nodes
//   grid   updateGrid                  v = p / m, f -> v^{n+1} with damping, the node conditions and reactions
//   G2P    gridToParticle              velocities (PIC/FLIP) and positions back to the particles
//   strain strainAndClosedFormStress or gridToParticle(.., true)   d eps = dt sym grad v at the particle
//   stress updateStresses              Material::update of every particle (material/material.hpp)
//
// USL, the default, runs the same phases fused into one pass over the particles
// (fused_transfer.cpp): each particle gathers from the updated grid (G2P), takes its strain
// increment and, where it has one, its closed-form stress, and scatters its mass, momentum and
// force into the next step's grid (the next step's P2G) while its fields are in cache. The
// particles without a closed form (cracked, near onset, smeared) are deferred: they take
// Material::update after the pass and scatter then. The fused pass therefore leaves the next
// step's P2G done: the grid "holds the state" (FusedPass::gridHoldsState) and the next step
// starts at the grid phase. Only this file sets that flag; anything that changes the state
// between steps (a restart, editState(), phases run by hand) calls rebuildGridNextStep(), and
// the next step rebuilds that scatter first (scatterState).
//
// The fused USL gives the plain sequence's results up to the order of the sums: within a part of
// the particles it adds the closed-form points before the deferred ones (1e-12 relative on the
// DEN; tests/mpm/den_test.cpp).
#include <omp.h>

#include "mpm/explicit/explicit_solver.hpp"

namespace ecm::mpm {

template <class Phase>
void ExplicitSolver::timed(StepPhase phase, Phase&& run) {
  const double start = omp_get_wtime();
  run();
  phaseSeconds_[static_cast<std::size_t>(phase)] += omp_get_wtime() - start;
}

void ExplicitSolver::advance() {
  const StepSetup& s = setup_;
  MpmState& st = state_;
  Particles& p = st.particles;
  GridFields& grid = st.grid;
  const Clock& clock = st.clock;
  if (s.scene.solver.explicitScheme.scheme == UpdateScheme::USL) {
    if (!fused_.gridHoldsState) {  // P2G of this step: first step, restart, state edited
      storeIntactStresses();      // (it scatters the stored stresses)
      fused_.shared = sharedMassAndVolume(p, s.materials.size());  // (the particles may have been edited)
      timed(StepPhase::Rebuild, [&] { scatterState(s, clock.step, p, grid, st.order, fused_); });
    }
    fused_.gridHoldsState = false;  // until the pass below has scattered every point anew
    timed(StepPhase::Grid, [&] {
      addLoads(s, clock.time, p, grid, st.loads);
      updateGrid(s, clock, grid, st.conditions, st.totals);
      if (!st.platens.empty()) applyPlatens(s, clock, grid, st.platens, &st.totals, true);
    });
    bool inGrid = false;  // G2P, strain, closed-form stresses, the next step's P2G
    intactStressesUnstored_ = true;  // the pass scatters the closed-form stresses without storing them
    timed(StepPhase::Fused, [&] { inGrid = gatherStressScatter(s, clock, grid, p, st.order, fused_); });
    timed(StepPhase::Stress, [&] { updateStresses(s, clock.step, p, st.totals, st.crackPaths, &fused_.deferred); });  // the deferred points
    if (inGrid) {  // (a stencil that left the grid is reported by the next step's scatterState)
      timed(StepPhase::DeferredScatter, [&] { scatterDeferred(s, p, grid, st.order, fused_); });  // their share of the next P2G
      fused_.gridHoldsState = true;
    }
  } else {
    phases();
  }
  st.clock.time += st.clock.dt;
  ++st.clock.step;
}

void ExplicitSolver::advanceByPhases() {
  phases();
  state_.clock.time += state_.clock.dt;
  ++state_.clock.step;
}

void ExplicitSolver::phases() {
  const StepSetup& s = setup_;
  MpmState& st = state_;
  Particles& p = st.particles;
  GridFields& grid = st.grid;
  const Clock& clock = st.clock;
  storeIntactStresses();          // the plain phases' P2G reads every stress (and their updates store them all)
  fused_.gridHoldsState = false;  // the plain phases leave no scatter for the next step
  const auto p2g = [&](unsigned what) {
    timed(StepPhase::P2G, [&] { particleToGrid(s, clock.step, p, grid, st.order, what); });
    if (what & kForces) timed(StepPhase::Grid, [&] { addLoads(s, clock.time, p, grid, st.loads); });
  };
  const auto gridUpdate = [&] {
    timed(StepPhase::Grid, [&] {
      updateGrid(s, clock, grid, st.conditions, st.totals);
      if (!st.platens.empty()) applyPlatens(s, clock, grid, st.platens, &st.totals, true);
    });
  };
  const auto velocities = [&] {
    timed(StepPhase::Grid, [&] {
      gridVelocities(s, clock, grid, st.conditions);
      if (!st.platens.empty()) applyPlatens(s, clock, grid, st.platens, nullptr, false);
    });
  };
  const auto g2p = [&](bool strain) { timed(StepPhase::G2P, [&] { gridToParticle(s, clock, grid, p, strain); }); };
  const auto stress = [&] { timed(StepPhase::Stress, [&] { updateStresses(s, clock.step, p, st.totals, st.crackPaths); }); };
  const auto strainStress = [&] {  // strain and closed-form stresses in one pass, then the others
    timed(StepPhase::Strain, [&] { strainAndClosedFormStress(s, clock.dt, grid, p, pending_, pendingPerThread_); });
    timed(StepPhase::Stress, [&] { updateStresses(s, clock.step, p, st.totals, st.crackPaths, &pending_); });
  };
  switch (s.scene.solver.explicitScheme.scheme) {
    case UpdateScheme::USF:  // update stress first: strain from the step's starting velocities
      p2g(kStencils | kMassMomentum);
      velocities();
      strainStress();  // = strain(); stress();
      p2g(kForces);
      gridUpdate();
      g2p(false);
      break;
    case UpdateScheme::USL:  // update stress last: strain from the updated grid velocities
      p2g(kStencils | kMassMomentum | kForces);
      gridUpdate();
      g2p(true);
      stress();
      break;
    case UpdateScheme::MUSL:  // modified USL: the grid velocities remapped from the updated particles
      p2g(kStencils | kMassMomentum | kForces);
      gridUpdate();
      timed(StepPhase::G2P, [&] { gridToParticleAndRemap(s, clock, grid, p, st.order); });  // = g2p(false); p2g(kMassMomentum);
      velocities();
      strainStress();  // = strain(); stress();
      break;
  }
}

}  // namespace ecm::mpm
