#pragma once
// One try at a piece of a load step (docs/implicit.md, "Load steps"): what the step prepares
// (prescribed components, platens, ties, loads), Newton's iterate and its trial, and, when the try
// fails, why. Plain data: the load stepping (load_stepping.cpp) reads it to decide what to try
// next, the commit (step_commit.cpp) to move the particles.
#include <Eigen/Sparse>
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "mpm/implicit/implicit_system.hpp"
#include "mpm/implicit/node_ties.hpp"
#include "mpm/implicit/platen_and_tie_unknowns.hpp"

namespace ecm::mpm {

struct ImplicitStepReport {
  double size = 0.0;        // the pseudo-time (or, under indirect control, the d tau) advanced
  double onsetOvershoot = 0.0;  // the most a point passed its onset by in the step (of its strength)
  int iterations = 0;       // Newton iterations of the converged attempt (all attempts in `total`)
  int totalIterations = 0;
  int cuts = 0;             // halvings needed
  int factorizations = 0;   // of the tangent, in all attempts
  double residual = 0.0;    // relative, at convergence
  long released = 0;        // snap-backs released at the material level in the step
  int relaxed = 0;          // 1: kept with a residual between tolerance and acceptTolerance
  int proximalSteps = 0;    // stabilised steps: the solves with dashpots (docs/implicit.md, "Stabilised steps")
  double dashpotWork = 0.0; // the energy their dashpots took: W_ext - d(strain energy) - d(dissipated) (N mm)
  double linearSolveSeconds = 0.0;
  long krylovIterations = 0;  // GMRES vectors on the kept factorisation (ImplicitSettings::krylovIterations)
};

// Why an attempt at a piece failed: what the load stepping does next depends on it.
enum class NewtonFailure {
  None,
  LeftGrid,         // a particle's shape-function support left the grid
  Material,         // a material update failed (its status says how; SnapBack among them)
  Singular,         // the tangent is singular
  NotConverged,     // Newton ran out of iterations or stalled (it keeps its best iterate)
  OnsetOvershoot,   // the piece carried a point past its onset by more than the scene allows
  ControlBlind,     // indirect control: c . du does not change with the load factor
};

struct Attempt {
  std::vector<std::uint8_t> prescribed;  // per node component
  Eigen::VectorXd du;                    // per node component (mm)
  Eigen::VectorXd external;              // loads and gravity at the step's end, per node component (N)
  Eigen::VectorXd externalStart;         // the same at the step's start
  Eigen::VectorXd startForce;            // the internal forces at the step's start (du = 0), on its geometry
  Eigen::VectorXd direction;             // indirect control: the driven components' reference (mm per unit load factor)
  // The platens (mpm/implicit/platen_and_tie_unknowns.hpp): per platen, which degrees of freedom are
  // prescribed in the step, their increments and (indirect control) their reference; the nodes
  // tied to their neighbours (mpm/implicit/node_ties.hpp); the change of unknowns (none without
  // platens and ties) and the reduced tangent last factorised.
  std::vector<std::array<bool, 3>> platenPrescribed;
  std::vector<Eigen::Vector3d> platenIncrement, platenDirection;
  std::vector<NodeTie> ties;
  std::optional<UnknownReduction> reduction;
  Eigen::SparseMatrix<double> reducedTangent;
  double dLambda = 0.0;                  // indirect control: the load factor's increment
  double dTau = 0.0;                     // indirect control: the opening's increment
  Trial trial;                           // at du
  ImplicitStepReport report;
  SnapBackPolicy snapBack = SnapBackPolicy::Stop;  // set by each attempt: Stop, or Release under the scene's release
  double reuseRatio = 0.1;               // ImplicitSettings::reuseRatio, 0 after a failed attempt (Newton proper)
  int maxIterations = 25;                // ImplicitSettings::maxIterations, 4 times that at the last halving
  bool lastResort = false;               // the last halving: no early stall test, its whole maxIterations
  bool stalled = false;                  // Newton ran out of iterations; du and trial hold its last iterate
  // A stabilised attempt (docs/implicit.md, "Stabilised steps"): the dashpots' alpha, and the
  // increments Newton starts from instead of the predictor (displacement control; nullptr: none).
  Dashpots dashpots;
  const Eigen::VectorXd* warmStart = nullptr;
  // The last halving under release keeps each point's release for the rest of the attempt
  // (docs/implicit.md, "Releases kept within a step").
  bool keepReleases = false;
  ReleasedStarts kept;
  const ReleasedStarts* keptStarts() const { return keepReleases ? &kept : nullptr; }
  // The points the attempt released: those of its trial, and with kept releases those of its
  // earlier iterates too, each counted once.
  long releases() const {
    if (!keepReleases) return trial.released;
    long count = static_cast<long>(kept.starts.size());
    for (const auto& [i, start] : trial.releases)
      if (kept.of.empty() || kept.of[i] < 0) ++count;
    return count;
  }
  const UnknownReduction* unknownReduction() const { return reduction ? &*reduction : nullptr; }
  // The tangent to factorise: K over the unknowns, or T^T K T with platens or ties (kept here).
  const Eigen::SparseMatrix<double>& tangentOf(const Trial& t) {
    if (!reduction) return t.tangent;
    reducedTangent = reduceTangent(*reduction, t.tangent);
    return reducedTangent;
  }

  UpdateStatus failedStatus = UpdateStatus::Converged;  // of the material update that failed
  // Why it failed: the iteration, the relative residual and the particle (SIZE_MAX: none).
  int failedIteration = 0;
  double failedResidual = 0.0;
  std::size_t failedParticle = SIZE_MAX;
  NewtonFailure reason = NewtonFailure::None;
  std::string why;  // the reason in words, for the report

  // Records why the attempt failed; returns false, for `return a.fail(...)`.
  bool fail(int iteration, double residual, NewtonFailure kind, std::string words) {
    failedIteration = iteration, failedResidual = residual, reason = kind, why = std::move(words);
    return false;
  }
  // A material update of `t` failed: the particle and its material's explanation.
  bool failInMaterial(int iteration, const Trial& t, const StepSetup& setup, const Particles& p) {
    failedParticle = t.failed;
    failedStatus = t.failure.status;
    return fail(iteration, 0.0, NewtonFailure::Material, setup.materials[p.material[t.failed]].explain(t.failure));
  }
};

}  // namespace ecm::mpm
