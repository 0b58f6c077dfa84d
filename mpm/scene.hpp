#pragma once
// The plain description of an MPM run: grid, materials, bodies, boundary conditions, loads and
// solver settings. Built in C++ (tests) or by the YAML reader (mpm/scene_yaml.hpp); checked
// once by validate(), the one checker of a scene's values; the solver trusts a validated scene.
#include <optional>
#include <string>
#include <vector>

#include "material/material.hpp"
#include "mpm/boundary.hpp"
#include "mpm/geometry.hpp"
#include "mpm/grid.hpp"
#include "mpm/shape_function.hpp"
#include "mpm/stop_when.hpp"

namespace ecm::mpm {

enum class UpdateScheme {
  USF,   // update stress first (strain from v^n of the grid)
  USL,   // update stress last (strain from v^{n+1})
  MUSL,  // modified USL: v^{n+1} re-mapped from the updated particle velocities
};
const char* toString(UpdateScheme s);

struct Damping {
  double local = 0.0;    // Cundall: f -= local |f| sign(v) per component, in [0, 1)
  double viscous = 0.0;  // f -= viscous m v (1/s)
};

// One term of an indirect control's combination: `coefficient` times the displacement component
// (0 x, 1 y) of the grid node nearest `at` (mm).
struct ControlTerm {
  Vec2 at = Vec2::Zero();
  int component = 1;
  double coefficient = 1.0;
};

// Implicit quasi-static solution (solver: {scheme: implicit_static}; docs/implicit.md). The
// scene's time is a pseudo-time: the load steps go `load_step` at a time to end_time, or, under
// indirect control, the combination of node displacements grows `step` mm per load step to
// `until` mm while the driven conditions follow the load factor.
struct ImplicitSettings {
  double tolerance = 1e-6;  // force residual relative to the loads, reactions and internal forces
  int maxIterations = 25;   // Newton iterations of a step before it is halved
  int maxHalvings = 8;
  double onsetOvershoot = 0.05;  // a load step may carry a point past its onset by this fraction of its strength
  double acceptTolerance = 1e-4; // a step whose Newton stalls below this residual is kept (counted)
  double loadStep = 0.0;    // pseudo-time per load step (s), displacement control
  bool umfpack = false;     // the LU: UMFPACK (the default when the build has it) or Eigen's SparseLU (docs/implicit.md)
  struct Indirect {
    std::vector<std::string> driven;  // conditions moved by the load factor
    Vec2 reference = Vec2(0.0, 1.0);  // their displacement per unit load factor (mm)
    std::vector<ControlTerm> terms;   // tau = sum of the terms
    double step = 0.0;                // d tau per load step (mm)
    double until = 0.0;               // tau at the end (mm)
    double from = 0.0;                // pseudo-time (s) of the load steps before the control takes over (load_step)
  };
  std::optional<Indirect> indirect;
};

struct SolverSettings {
  UpdateScheme scheme = UpdateScheme::USL;
  ShapeFunction shapeFunction = ShapeFunction::Linear;
  double flip = 1.0;    // PIC/FLIP blend: 1 = FLIP, 0 = PIC
  double cfl = 0.3;     // dt = cfl * min cell size / max P-wave speed; (0, 1]
  Damping damping;
  Vec2 gravity = Vec2::Zero();  // mm/s^2
  EffectiveSizeRule effectiveSize = EffectiveSizeRule::SquareRoot;  // enriched materials: SquareRoot or Oriented
  int substepLevels = 4;        // non-converged updates are retried with 2, 4, ... 2^levels sub-steps
  // Enriched points whose loading branch turns back (no stable root of Eq. (6) under the
  // increment): Release lets the band fail onto its stable branch (counted, reported); Stop
  // stops the run with the point's position and state.
  SnapBackPolicy snapBack = SnapBackPolicy::Release;
  std::optional<ImplicitSettings> implicit;  // scheme: implicit_static (then `scheme` is unused)
};

// When a run writes its checkpoint (mpm/checkpoint.hpp) besides on a stop request: every N steps
// and/or every M minutes of wall time (0: never).
struct CheckpointSettings {
  long everySteps = 0;
  double everyMinutes = 0.0;
};

struct Scene {
  std::string name = "scene";
  std::string preset;       // the preset that set the discretisation knobs (mpm/presets.hpp), or empty
  Grid grid;
  double thickness = 1.0;  // mm (plane stress: the plate; plane strain: the slice)
  std::vector<MaterialParams> materials;
  std::vector<Body> bodies;
  int particlesPerCell = 2;  // k: k x k particles per cell
  std::vector<NodeCondition> conditions;
  std::vector<Load> loads;
  SolverSettings solver;
  double endTime = 0.0;         // s: the latest end
  std::optional<StopWhen> stopWhen;  // an earlier end by a condition's load (mpm/stop_when.hpp)
  double outputInterval = 0.0;  // s between output steps (0: only the first and last)
  int snapshotEvery = 1;        // a VTU snapshot at every N-th output step (and the last)
  std::vector<double> particleSnapshots;  // s, increasing: particles_t<time>.csv at each (maps of states)
  CheckpointSettings checkpoint;

  // Throws io::ValueError naming the key path of the value that is wrong ("solver.cfl",
  // "materials[1]"), so that the YAML reader can give its line.
  void validate() const;
};

}  // namespace ecm::mpm
