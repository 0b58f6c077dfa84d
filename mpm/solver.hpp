#pragma once
// The explicit MPM solver: particles and grid as arrays, one step = the phases in order.
// Each phase is a public function so that it can be tested on its own.
#include <memory>
#include <vector>

#include "material/material.hpp"
#include "mpm/errors.hpp"
#include "mpm/grid.hpp"
#include "mpm/particles.hpp"
#include "mpm/scene.hpp"

namespace ecm::mpm {

namespace detail {
struct ScatterTarget;  // mpm/transfer_kernels.hpp
}

// What particle-to-grid scatters (bit flags).
enum Transfer : unsigned {
  kStencils = 1u,      // locate the particles' stencils (Particles::stencilAt) at their positions first;
                       // every other transfer of the step expands the weights from them
  kMassMomentum = 2u,  // mass and momentum
  kForces = 4u,        // internal and external forces
};

// The runtime state of a node condition: its nodes, the reaction of the step and the
// prescribed displacement so far.
struct ConditionState {
  std::vector<std::int32_t> nodes;
  Vec2 reaction = Vec2::Zero();      // N: sum over the nodes of the constraint forces of the last step
  Vec2 displacement = Vec2::Zero();  // mm: integral of the prescribed velocity (of the field at its origin)
};

struct LoadState {
  std::vector<std::int32_t> members;  // nodes or particles
  Vec2 applied = Vec2::Zero();        // N: the total force applied in the last step
};

// Energies (N mm = mJ). Kinetic and strain are of the present state; the others accumulate.
struct Energies {
  double kinetic = 0.0;
  double strain = 0.0;        // sum of V sigma.eps / 2 (recoverable for elastic and secant unloading)
  double externalWork = 0.0;  // loads, gravity and reactions
  double dissipated = 0.0;    // by the materials (damage)
  double damping = 0.0;       // removed by local and viscous damping
};

class Solver {
 public:
  // Seeds the particles of a validated scene (Scene::validate; readScene returns one). threads > 0: exactly that many; 0: automatic,
  // the OpenMP default but at most one thread per kParticlesPerThread particles (for small
  // scenes fork/join and barriers cost more than they save).
  explicit Solver(Scene scene, int threads = 0);
  static constexpr std::size_t kParticlesPerThread = 4096;

  // One explicit step (mpm/step.cpp): the phases of the scene's update scheme in order; USL, the
  // default, runs them fused into one pass over the particles (fused_transfer.cpp).
  void advance();
  // The same step as the plain phase sequence, for every scheme (USL unfused): the reference
  // the fused pass is tested against.
  void advanceByPhases();

  // --- the phases (step.cpp puts them in order); run by hand before advance(), call
  // rebuildGridNextStep() first ---
  void particleToGrid(unsigned transfer);
  void updateGrid();          // v^n = p/m, forces and damping -> v^{n+1}, conditions, reactions
  void gridVelocities();      // v = p/m with the velocity conditions (USF strain, MUSL remap)
  // Velocities (PIC/FLIP), positions and optionally strain increments (USF, MUSL; USL runs the
  // fused pass of fused_transfer.cpp instead).
  void gridToParticle(bool withStrainIncrements);
  void computeStrainIncrements();  // from the grid velocities
  // The material update (sub-stepping on failure) of every particle, or of deferred_ only.
  void updateStresses(bool deferredOnly = false);

  // --- state ---
  const Scene& scene() const { return scene_; }
  const Particles& particles() const { return particles_; }
  // Particles to change between steps (tests, set-ups, restarts): the next step rebuilds the
  // grid's scatter from them (rebuildGridNextStep) instead of the one the fused USL pass left.
  Particles& editParticles() {
    rebuildGridNextStep();
    return particles_;
  }
  void rebuildGridNextStep() { gridHoldsState_ = false; }
  const GridFields& grid() const { return grid_; }
  const std::vector<ConditionState>& conditions() const { return conditions_; }
  const std::vector<LoadState>& loads() const { return loads_; }
  const std::vector<Material>& materials() const { return materials_; }
  double time() const { return time_; }
  long step() const { return step_; }
  double timeStep() const { return dt_; }
  void setTimeStep(double dt) { dt_ = dt; }  // for tests; the constructor sets it from the CFL number
  int threads() const { return threads_; }
  Energies energies() const;
  double damage(std::size_t p) const;          // 0 intact .. 1 fully damaged
  EffectiveSize effectiveSize() const { return size_; }
  long substepped() const { return substepped_; }  // material updates that needed sub-stepping so far
  long snapBackReleases() const { return released_; }  // enriched updates that released a snap-back so far

  // What carries over from one step to the next besides the particles (for checkpoints,
  // mpm/checkpoint.hpp). The grid and the particles' stencils are rebuilt by every step.
  struct StepState {
    double time = 0.0, timeStep = 0.0;
    long step = 0;
    double externalWork = 0.0, dissipated = 0.0, damping = 0.0;
    long substepped = 0, released = 0;
    std::vector<Vec2> reactions, conditionDisplacements;  // per condition
    std::vector<Vec2> appliedLoads;                       // per load
    std::vector<std::uint32_t> deferred;                  // USL: the last step's deferred points (fused_transfer.cpp)
  };
  StepState stepState() const;
  // Throws std::invalid_argument when the condition or load counts differ from the scene's.
  void restoreStepState(const StepState& s);

 private:
  Scene scene_;
  int threads_;
  double dt_ = 0.0;
  double time_ = 0.0;
  long step_ = 0;
  Vec2 invCell_, halfWidth_;
  EffectiveSize size_;
  Particles particles_;
  GridFields grid_;
  std::vector<GridAccumulator> scratch_;  // one per extra thread
  std::vector<Material> materials_;
  std::vector<std::uint32_t> deferred_;  // USL: particles left to updateStresses, in index order
  std::vector<std::vector<std::uint32_t>> deferredPerThread_;
  std::vector<ConditionState> conditions_;
  std::vector<std::uint8_t> constrained_;  // per node: bit 0 x, bit 1 y is prescribed (no damping there)
  std::vector<LoadState> loads_;
  double externalWork_ = 0.0, dissipated_ = 0.0, damping_ = 0.0;
  long substepped_ = 0;
  long released_ = 0;

  // USL fused (fused_transfer.cpp): the grid holds the scatter of the present particles (their
  // mass, momentum and forces, loads not yet added). Set only by step.cpp (and cleared by
  // rebuildGridNextStep).
  bool gridHoldsState_ = false;
  void scatterState();         // rebuild the scatter of the present particles, in the fused order
  // G2P, closed-form stresses and the next step's scatter in one pass; false when a stencil
  // left the grid (the deferred points then do not scatter; the next scatterState reports it).
  bool gatherStressScatter();
  void scatterDeferred();      // the deferred points' scatter, after updateStresses; sums the parts
  detail::ScatterTarget part(int t);  // scatter buffer of part t: the grid (0) or scratch_[t - 1]
  void sumScatterBuffers(unsigned what, int parts);
  void addScatterBuffer(int t, unsigned what, int lo, int hi);
  // Fused USL: the scatter buffers summed only over the nodes their part touched (a part's
  // particles are contiguous in the seeding order, so a band of the grid), which are also the
  // only nodes the next step has to zero.
  std::vector<std::pair<int, int>> spans_;         // per part: lowest, highest stencil base of this step
  std::vector<std::pair<int, int>> touched_;       // per scratch buffer: nodes [lo, hi) not zero
  void sumTouchedNodes();

  void phases();  // the plain phase sequence of the scheme (step.cpp)
  void applyVelocityConditions(bool reactions);
  void addLoads();
  [[noreturn]] void throwLeftGrid(std::size_t p) const;
  [[noreturn]] void throwNotFinite(std::size_t p) const;
};

}  // namespace ecm::mpm
