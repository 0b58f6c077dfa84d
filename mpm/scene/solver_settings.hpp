#pragma once
// How a scene is solved (the `solver:` map; mpm/scene/scene_yaml.hpp): one type with the settings
// both solvers read, the explicit scheme's part and the implicit solver's part. Every default is
// written here once; the solvers read these settings as they are.
#include <optional>
#include <string>
#include <vector>

#include "material/material.hpp"
#include "mpm/core/shape_function.hpp"

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

// The explicit scheme (explicit dynamics with a CFL time step; mpm/explicit/).
struct ExplicitSettings {
  UpdateScheme scheme = UpdateScheme::USL;
  double flip = 1.0;  // PIC/FLIP blend: 1 = FLIP, 0 = PIC
  double cfl = 0.3;   // dt = cfl * min cell size / max P-wave speed; (0, 1]
  Damping damping;
};

// The sparse LU of the implicit steps (docs/implicit.md): UMFPACK when the build has it (found at
// build time, loaded at the first factorisation), Eigen's SparseLU otherwise.
enum class LinearSolverKind { SparseLU, Umfpack, Amg };
const char* toString(LinearSolverKind k);
bool available(LinearSolverKind k);
inline LinearSolverKind defaultLinearSolver() {
  return available(LinearSolverKind::Umfpack) ? LinearSolverKind::Umfpack : LinearSolverKind::SparseLU;
}

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
  double tolerance = 1e-6;  // |residual| <= tolerance * max(|loads|, |reactions|, |internal forces|)
  int maxIterations = 25;   // Newton iterations of a step before it is halved
  int maxHalvings = 8;      // halvings of a step before the run fails
  // A load step may carry a point past its onset by this fraction of its strength; a piece
  // whose trial goes further is cut (docs/implicit.md, "Load steps").
  double onsetOvershoot = 0.05;
  // A step whose Newton, factorising at every iteration, stalls with a relative residual at most
  // this is kept and counted (a point at the kink between loading and unloading can keep Newton
  // from the tolerance at any step size; the next step's Newton takes the residual up).
  double acceptTolerance = 1e-4;
  // A load step whose smallest piece does not converge is solved with a dashpot in parallel at
  // its cracked points, alpha D_e d eps, and then again with alpha / 10, alpha / 100 and 0, each
  // from the last solution; the step keeps the smallest alpha that converged (docs/implicit.md,
  // "Stabilised steps"). 0: never (the run stops there).
  double stabilization = 1e-2;
  double loadStep = 0.0;    // pseudo-time per load step (s), displacement control
  LinearSolverKind linearSolver = defaultLinearSolver();
  struct Indirect {
    std::vector<std::string> driven;  // conditions moved by the load factor
    Vec2 reference = Vec2(0.0, 1.0);  // their displacement per unit load factor (mm)
    std::vector<ControlTerm> terms;   // tau = sum of the terms
    std::string gauge;                // or: tau = that gauge's reading (mpm/scene/gauge.hpp; then no terms)
    double step = 0.0;                // d tau per load step (mm)
    double until = 0.0;               // tau at the end (mm)
    double from = 0.0;                // pseudo-time (s) of the load steps before the control takes over (load_step)
  };
  std::optional<Indirect> indirect;

  // Tuning of the solver, not read from scenes (docs/implicit.md):
  // The factorised tangent is kept while Newton's residual falls by at least this factor per
  // iteration, and refactorised at the current iterate otherwise ("Fewer factorisations"); the
  // predictor of a step takes the last factorisation. 0: a factorisation at every iteration.
  double reuseRatio = 0.1;
  // Newton's step on the current tangent by GMRES preconditioned with the kept factorisation
  // ("Krylov on the kept factorisation"): at most krylovIterations Krylov vectors, a fresh
  // factorisation where they do not reach krylovTolerance. 0: the kept factorisation's step as it
  // is (modified Newton). The LU solvers only: AMG is GMRES already.
  int krylovIterations = 16;  // docs/implicit.md, "Two threads on the kept factors": 8 until the solves got cheaper
  // The relative residual to which GMRES solves a Newton step's system (inexact Newton: Newton's
  // own tolerance is on the forces), with the kept factorisation or with AMG ("The AMG solver").
  double krylovTolerance = 1e-3;
  // Indirect control: a step's Newton starts from the last step's increments, scaled to its
  // opening ("The extrapolated start"); false: from du = 0.
  bool extrapolate = true;
  // Adaptive pieces: a piece converged in at most `easyIterations` Newton iterations doubles the
  // next one, in at least `hardIterations` halves it ("Load steps").
  int easyIterations = 4;
  int hardIterations = 10;
};

// Where an enriched point may open its band (docs/model.md, "Crack paths").
enum class CrackPathRule {
  Tracked,  // only on the crack paths the run tracks, with their normals
  Free,     // wherever it reaches onset, normal to its own principal stress
};
const char* toString(CrackPathRule r);

struct SolverSettings {
  // Read by both solvers.
  ShapeFunction shapeFunction = ShapeFunction::Linear;
  EffectiveSizeRule effectiveSize = EffectiveSizeRule::SquareRoot;  // enriched materials: SquareRoot or Oriented
  Vec2 gravity = Vec2::Zero();  // mm/s^2
  int substepLevels = 4;        // non-converged updates are retried with 2, 4, ... 2^levels sub-steps
  // Enriched points whose loading branch turns back (no stable root of Eq. (6) under the
  // increment): Release lets the band fail onto its stable branch (counted, reported); Stop
  // stops the run with the point's position and state (docs/model.md, "Snap-back on the path").
  SnapBackPolicy snapBack = kDefaultSnapBack;
  // Tracked by default: a crack that grows through a stress gradient runs where a cohesive crack
  // runs only on a tracked path (docs/model.md, "Crack paths"); Free is the paper's own rule.
  CrackPathRule crackPath = CrackPathRule::Tracked;
  // The scheme: explicit (explicitScheme) unless `implicit` is set (scheme: implicit_static).
  ExplicitSettings explicitScheme;
  std::optional<ImplicitSettings> implicit;
};

}  // namespace ecm::mpm
