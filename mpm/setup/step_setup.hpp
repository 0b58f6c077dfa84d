#pragma once
// What both solvers start from and share: the setup of a seeded scene (StepSetup: the scene,
// its materials, the grid in cell units, the prescribed components, the threads), the runtime
// state of its conditions and loads, the run's totals and energies. Plain structs; the explicit
// step's own state is mpm/explicit/state.hpp, the implicit solver's mpm/implicit/implicit_solver.hpp.
#include <cstdint>
#include <vector>

#include "material/material.hpp"
#include "mpm/core/grid.hpp"
#include "mpm/core/particles.hpp"
#include "mpm/scene/scene.hpp"

namespace ecm::mpm {

// What the steps read and never change during a run: the scene, its materials, the grid
// geometry in cell units and the number of threads.
struct StepSetup {
  Scene scene;
  std::vector<Material> materials;         // one per scene material, in its order
  double fullNodeMass = 0.0;               // t: rho h_x h_y t of the lightest material, a node's mass inside a body
  Vec2 invCell = Vec2::Ones();             // 1/mm
  Vec2 halfWidth = Vec2::Zero();           // uGIMP half-size of a particle's domain, in cells
  EffectiveSize size;                      // the effective size H of every point (docs/model.md)
  std::vector<std::uint8_t> constrained;   // per node: bit 0 x, bit 1 y is prescribed (no damping there)
  int threads = 1;
};

// What the run adds up over its steps (N mm = mJ for the energies).
struct RunTotals {
  double externalWork = 0.0;  // loads, gravity and reactions
  double dissipated = 0.0;    // by the materials (damage)
  double damping = 0.0;       // removed by local and viscous damping
  long substepped = 0;        // material updates that needed sub-stepping
  long released = 0;          // enriched updates that released a snap-back
  long massScaled = 0;        // explicit: node updates whose mass was raised to keep them stable (grid_update.cpp)
};

// Energies (N mm = mJ). Kinetic and strain are of the present state; the others accumulate.
struct Energies {
  double kinetic = 0.0;
  double strain = 0.0;        // sum of V sigma.eps / 2 (recoverable for elastic and secant unloading)
  double externalWork = 0.0;  // loads, gravity and reactions
  double dissipated = 0.0;    // by the materials (damage)
  double damping = 0.0;       // removed by local and viscous damping
};

// The runtime state of a node condition: its nodes, the reaction of the step and the
// prescribed displacement so far.
struct ConditionState {
  std::vector<std::int32_t> nodes;
  Vec2 reaction = Vec2::Zero();      // N: sum over the nodes of the constraint forces of the last step
  Vec2 displacement = Vec2::Zero();  // mm: integral of the prescribed velocity (of the field at its origin)
};

// The runtime state of a rigid platen (mpm/scene/platen.hpp): its nodes, its reference point, where
// it is and what it puts on the specimen. Degrees of freedom in the order x, y, rotation.
struct PlatenState {
  std::vector<std::int32_t> nodes;              // sorted, each once
  Vec2 reference = Vec2::Zero();                // mm
  Eigen::Vector3d displacement = Eigen::Vector3d::Zero();  // mm, mm, rad
  Eigen::Vector3d force = Eigen::Vector3d::Zero();         // N, N, N mm (moment about the reference): on the specimen, last step
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();      // mm/s, mm/s, rad/s (explicit: of the last step)
};

struct LoadState {
  std::vector<std::int32_t> members;  // nodes or particles
  Vec2 applied = Vec2::Zero();        // N: the total force applied in the last step
};

// The setup of a scene whose particles are seeded: threads > 0 exactly that many, 0 automatic
// (the OpenMP default, but at most one thread per `particlesPerThread` particles).
StepSetup makeStepSetup(Scene scene, std::size_t particles, int threads, std::size_t particlesPerThread);
// The conditions' nodes (throws std::invalid_argument naming a condition whose box holds no
// grid node) and the loads' members, nodes or particles (naming a load whose box holds none).
std::vector<ConditionState> conditionStates(const Scene& scene);
std::vector<LoadState> loadStates(const Scene& scene, const Particles& particles);
// The platens' nodes and reference points. Throws std::invalid_argument naming a platen that
// shares a node with another platen or with a condition, or whose rotation is not held on fewer
// than two nodes (one node cannot carry a rotation).
std::vector<PlatenState> platenStates(const Scene& scene);

}  // namespace ecm::mpm
