#pragma once
// The phases of an explicit MPM step, as functions over the plain state of mpm/explicit/state.hpp.
// mpm/explicit/step.cpp puts them in order for each update scheme; each can be run and tested alone.
//   P2G     particleToGrid (transfer.cpp)       mass, momentum and forces to the nodes
//   loads   addLoads (grid_update.cpp)          the scene's loads at the nodes
//   grid    updateGrid (grid_update.cpp)        v = p / m, forces and damping -> v^{n+1}, conditions, reactions
//   G2P     gridToParticle (transfer.cpp)       velocities (PIC/FLIP), positions, optionally strain increments
//   strain  strainAndClosedFormStress           d eps = dt sym grad v at the particle (and the closed-form stress)
//   stress  updateStresses (stress_update.cpp)  Material::update of the particles
// A phase that finds a particle outside the grid, a non-finite value or a failed material update
// throws SimulationError (mpm/core/errors.hpp) naming the step, the particle and where it is.
#include <cstdint>
#include <vector>

#include "mpm/explicit/state.hpp"

namespace ecm::mpm {

// What particle-to-grid scatters (bit flags).
enum Transfer : unsigned {
  kStencils = 1u,      // locate the particles' stencils (Particles::stencilAt) at their positions first;
                       // every other transfer of the step expands the weights from them
  kMassMomentum = 2u,  // mass and momentum
  kForces = 4u,        // internal forces and gravity (the loads: addLoads)
};

// The state at time 0: the particles, the grid and its scatter order, the conditions' and
// loads' members, and dt from the CFL number. Throws std::invalid_argument when a condition or
// load box holds no node or particle.
MpmState initialState(const StepSetup& setup, Particles particles);

// P2G: zeroes what `what` scatters and sums it from every particle in the order of
// mpm/explicit/scatter_order.hpp (kStencils: plans the order, locates the stencils, measures their rows
// and lists the far particles; otherwise the plan of the last kStencils transfer). step: the
// steps taken, for the report of a particle outside the grid.
void particleToGrid(const StepSetup& setup, long step, Particles& particles, GridFields& grid, ScatterOrder& order,
                    unsigned what);
// The loads of the scene at `time`, added to the grid's external forces.
void addLoads(const StepSetup& setup, double time, const Particles& particles, GridFields& grid,
              std::vector<LoadState>& loads);
// v^n = p/m, forces and damping -> v^{n+1}, the velocity conditions with their reactions; adds
// the damping and external work of the step.
void updateGrid(const StepSetup& setup, const Clock& clock, GridFields& grid, std::vector<ConditionState>& conditions,
                RunTotals& totals);
// v = p/m with the velocity conditions, no forces (USF strain, MUSL remap).
void gridVelocities(const StepSetup& setup, const Clock& clock, GridFields& grid,
                    std::vector<ConditionState>& conditions);
// The rigid platens (platen_update.cpp): their nodes' velocities made one rigid body's, after
// updateGrid (withForces: the step's forces, damping and the force histories act; given the
// totals, the platens' forces and displacements are recorded and their work added) or after
// gridVelocities (no forces).
void applyPlatens(const StepSetup& setup, const Clock& clock, GridFields& grid, std::vector<PlatenState>& platens,
                  RunTotals* totals, bool withForces);
// G2P: velocities (PIC/FLIP), positions and, withStrainIncrements, the strain increments.
void gridToParticle(const StepSetup& setup, const Clock& clock, const GridFields& grid, Particles& particles,
                    bool withStrainIncrements);
// The strain increments and, in the same pass, the closed-form stresses (elastic and intact
// points far from onset, Material::closedFormStress); the other points are listed in `deferred`
// (index order) with their increments, for updateStresses. The same per-point results as taking
// the increments first and updateStresses on every point after, one pass over the particles fewer.
void strainAndClosedFormStress(const StepSetup& setup, double dt, const GridFields& grid, Particles& particles,
                               std::vector<std::uint32_t>& deferred,
                               std::vector<std::vector<std::uint32_t>>& deferredPerThread);
// MUSL: grid-to-particle (velocities, positions) and the remap of the new particle velocities
// to the grid's momentum with the step's stencils, in one pass in the scatter order of the
// step's first particleToGrid: the same results as gridToParticle then
// particleToGrid(kMassMomentum). The grid's mass is that particleToGrid's, kept: remapped with
// the same stencils, masses and order of sums it would come out the same, bit for bit.
void gridToParticleAndRemap(const StepSetup& setup, const Clock& clock, GridFields& grid, Particles& particles,
                            const ScatterOrder& order);
// The material update (sub-stepping on failure) of every particle, or of `only` (sorted
// particle indices) when it is given; adds the dissipation and the sub-step and release counts.
// Tracked crack paths: an intact point off every path stays intact, and the paths grow after the
// updates (mpm/setup/crack_paths.hpp).
void updateStresses(const StepSetup& setup, long step, Particles& particles, RunTotals& totals, CrackPaths& paths,
                    const std::vector<std::uint32_t>* only = nullptr);
// Stores the stress of every point whose stress follows its strain (Material::stressFollowsStrain:
// elastic, intact enriched) as a : strain, the product every update of such a point ends with:
// bitwise what the fused pass computed and did not store.
void storeStressesOfIntactPoints(const StepSetup& setup, Particles& particles);

// The fused USL pass (fused_transfer.cpp): G2P, strain, closed-form stresses and the next step's
// P2G in one sweep over the particles.
// The scatter of the present particles in the order the pass below left it (first step,
// restart, edited particles): bitwise the grid the pass leaves.
void scatterState(const StepSetup& setup, long step, Particles& particles, GridFields& grid, ScatterOrder& order,
                  const FusedPass& fused);
// G2P, strain, closed-form stresses and the next step's scatter in a planned `order`; the points without a closed
// form go to fused.deferred. The closed-form stresses are scattered, not stored (except a far
// point's, which scatters later): storeStressesOfIntactPoints stores them. False when a stencil left the grid (the deferred points then do
// not scatter; the next scatterState reports it).
bool gatherStressScatter(const StepSetup& setup, const Clock& clock, GridFields& grid, Particles& particles,
                         ScatterOrder& order, FusedPass& fused);
// The deferred points' scatter after their updateStresses, then the far points' one by one.
void scatterDeferred(const StepSetup& setup, Particles& particles, GridFields& grid, const ScatterOrder& order,
                     const FusedPass& fused);

}  // namespace ecm::mpm
