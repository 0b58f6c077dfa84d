#pragma once
// The explicit MPM solver: a scene's setup and state (mpm/explicit/state.hpp) and the step that advances
// them (mpm/explicit/step.cpp puts the phases of mpm/explicit/phases.hpp in order).
#include <array>
#include <vector>

#include "mpm/core/errors.hpp"
#include "mpm/explicit/phases.hpp"
#include "mpm/explicit/state.hpp"

namespace ecm::mpm {

// The phases a step's wall time is booked to (ExplicitSolver::phaseSeconds, summary.json "phase_seconds").
enum class StepPhase {
  P2G,              // particle-to-grid
  Grid,             // loads, the grid update, velocity conditions
  G2P,              // grid-to-particle
  Strain,           // strain increments (USF, MUSL)
  Stress,           // material updates (USL fused: the deferred points only)
  Fused,            // the fused USL pass: G2P, strain, closed-form stress, the next P2G
  DeferredScatter,  // the fused USL pass's deferred and far points' scatter
  Rebuild,          // rebuilding the fused scatter (first step, restart, edited state)
};
inline constexpr std::size_t kStepPhases = 8;
const char* toString(StepPhase p);

class ExplicitSolver {
 public:
  // Seeds the particles of a validated scene (Scene::validate; readScene returns one). threads > 0: exactly that many; 0: automatic,
  // the OpenMP default but at most one thread per kParticlesPerThread particles (for small
  // scenes fork/join and barriers cost more than they save).
  explicit ExplicitSolver(Scene scene, int threads = 0);
  static constexpr std::size_t kParticlesPerThread = 4096;

  // One explicit step (mpm/explicit/step.cpp): the phases of the scene's update scheme in order; USL, the
  // default, runs them fused into one pass over the particles (fused_transfer.cpp).
  void advance();
  // The same step as the plain phase sequence, for every scheme (USL unfused): the reference
  // the fused pass is tested against.
  void advanceByPhases();

  // --- setup and state ---
  const StepSetup& setup() const { return setup_; }
  const Scene& scene() const { return setup_.scene; }
  const std::vector<Material>& materials() const { return setup_.materials; }
  EffectiveSize effectiveSize() const { return setup_.size; }
  int threads() const { return setup_.threads; }
  // The state and the particles with every stress stored. The fused USL pass leaves the stress
  // of an elastic or intact point (a : strain) unstored: 48 bytes of memory traffic less per
  // point and step (docs/model.md, "An intact point's stress"); these accessors store them first,
  // bitwise what the step computed. A reference kept across advance() sees the stresses as of
  // the last call: call particles() again after stepping.
  const MpmState& state() const {
    storeIntactStresses();
    return state_;
  }
  const Particles& particles() const {
    storeIntactStresses();
    return state_.particles;
  }
  // The particles as the last step left them, for readers of positions, velocities, strains and
  // bands every step (the gauges): an intact point's `stress` may be unstored (particles() stores it).
  const Particles& kinematics() const { return state_.particles; }
  const GridFields& grid() const { return state_.grid; }
  const std::vector<ConditionState>& conditions() const { return state_.conditions; }
  const std::vector<PlatenState>& platens() const { return state_.platens; }
  const std::vector<LoadState>& loads() const { return state_.loads; }
  double time() const { return state_.clock.time; }
  long step() const { return state_.clock.step; }
  double timeStep() const { return state_.clock.dt; }
  void setTimeStep(double dt) { state_.clock.dt = dt; }  // for tests; the constructor sets it from the CFL number
  Energies energies() const;
  double damage(std::size_t p) const;  // 0 intact .. 1 fully damaged
  long substepped() const { return state_.totals.substepped; }      // material updates that needed sub-stepping so far
  long massScaled() const { return state_.totals.massScaled; }      // node updates with a raised mass so far
  long snapBackReleases() const { return state_.totals.released; }  // enriched updates that released a snap-back so far
  // Wall time spent in each phase of the steps so far (s; not kept by a checkpoint).
  double phaseSeconds(StepPhase p) const { return phaseSeconds_[static_cast<std::size_t>(p)]; }

  // The state to change between steps (tests, set-ups, restarts, phases run by hand): the next
  // step rebuilds the grid's scatter from the particles (rebuildGridNextStep) instead of using
  // the one the fused USL pass left.
  MpmState& editState() {
    storeIntactStresses();
    rebuildGridNextStep();
    return state_;
  }
  Particles& editParticles() { return editState().particles; }
  void rebuildGridNextStep() { fused_.gridHoldsState = false; }

  // What carries over from one step to the next besides the particles (for checkpoints,
  // mpm/explicit/explicit_checkpoint.hpp). The grid and the particles' stencils are rebuilt by every step.
  struct StepState {
    double time = 0.0, timeStep = 0.0;
    long step = 0;
    double externalWork = 0.0, dissipated = 0.0, damping = 0.0;
    long substepped = 0, released = 0, massScaled = 0;
    std::vector<Vec2> reactions, conditionDisplacements;  // per condition
    std::vector<Vec2> appliedLoads;                       // per load
    std::vector<std::uint32_t> deferred;                  // USL: the last step's deferred points (fused_transfer.cpp)
  };
  StepState stepState() const;
  // Throws std::invalid_argument when the condition or load counts differ from the scene's.
  void restoreStepState(const StepState& s);

 private:
  StepSetup setup_;
  MpmState state_;
  FusedPass fused_;  // written only by step.cpp's fused USL step (and cleared by rebuildGridNextStep)
  // USF, MUSL: the points the strain pass left to updateStresses (step.cpp).
  std::vector<std::uint32_t> pending_;
  std::vector<std::vector<std::uint32_t>> pendingPerThread_;

  // The fused pass has left intact points' stresses unstored since the last storeIntactStresses().
  // Set by step.cpp only; a const accessor stores them (the ExplicitSolver is never a const object once
  // it has stepped, so the stores below write to a mutable object).
  mutable bool intactStressesUnstored_ = false;
  void storeIntactStresses() const;

  std::array<double, kStepPhases> phaseSeconds_{};
  void phases();  // the plain phase sequence of the scheme (step.cpp)
  template <class Phase>
  void timed(StepPhase phase, Phase&& run);
};

}  // namespace ecm::mpm
