// The load stepping of the implicit solver (mpm/implicit/implicit_solver.hpp): the adaptive
// piece, the retries and halvings of a piece whose Newton fails, and the failure a run reports
// when even the smallest piece fails (docs/implicit.md, "Load steps").
#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "mpm/core/errors.hpp"
#include "mpm/implicit/displacement_control.hpp"
#include "mpm/implicit/implicit_solver.hpp"
#include "mpm/implicit/newton.hpp"

namespace ecm::mpm {

namespace {

// The run's failure kind of an attempt that failed on the smallest piece.
FailureKind failureKindOf(NewtonFailure reason, UpdateStatus material) {
  switch (reason) {
    case NewtonFailure::LeftGrid: return FailureKind::LeftGrid;
    case NewtonFailure::Material: return material == UpdateStatus::SnapBack ? FailureKind::SnapBack : FailureKind::MaterialFailure;
    case NewtonFailure::Singular: return FailureKind::SingularTangent;
    case NewtonFailure::OnsetOvershoot: return FailureKind::OnsetOvershoot;
    case NewtonFailure::ControlBlind: return FailureKind::ControlBlind;
    case NewtonFailure::NotConverged:
    case NewtonFailure::None: break;
  }
  return FailureKind::NewtonNotConverged;
}

}  // namespace

bool ImplicitSolver::solvePiece(const IndirectControl* control, double piece, Attempt& a) {
  if (!prepare(control ? 0.0 : piece, control, a)) return false;
  const StepContext context{setup_, particles_, geometry_, settings_, factors_, factorKey()};
  if (control) {
    IndirectControlStep problem(context, *control, piece, lastIncrement_, a);
    return solveNewton(problem, context, a);
  }
  DisplacementControl problem(context, a);
  return solveNewton(problem, context, a);
}

// Proximal steps (docs/implicit.md, "Stabilised steps"): each solves the piece with dashpots that
// stretch from the last one's solution, so that the sequence walks down to a state in equilibrium
// without them, which Newton then finishes from there.
bool ImplicitSolver::solveStabilized(double piece, Attempt& result) {
  const auto attempt = [&](const Dashpots& dashpots, const Eigen::VectorXd* from, int iterations, Attempt& a) {
    a.reuseRatio = 0.0;  // Newton proper
    a.maxIterations = iterations;
    a.lastResort = true;
    a.snapBack = setup_.scene.solver.snapBack == SnapBackPolicy::Release ? SnapBackPolicy::Release : SnapBackPolicy::Stop;
    a.dashpots = dashpots;
    a.warmStart = from;
    return solvePiece(nullptr, piece, a);
  };
  double alpha = settings_.stabilization, relative = INFINITY;
  const double smallest = alpha / 64.0;  // a settled sequence weakens its dashpots to this
  Eigen::VectorXd from;  // the last proximal step's solution (empty: the step's start)
  for (int k = 0; k < kMaxProximalSteps; ++k) {
    Attempt a;
    const Eigen::VectorXd* start = from.size() > 0 ? &from : nullptr;
    if (!attempt({alpha, start}, start, 4 * settings_.maxIterations, a)) {
      if (a.reason != NewtonFailure::NotConverged || alpha >= kLargestStabilization) {
        result = std::move(a);
        return false;
      }
      alpha = std::min(4.0 * alpha, kLargestStabilization);  // stiffer dashpots: a shorter proximal step
      continue;
    }
    from = a.du;
    // Equilibrium without the dashpots: the residual of the material's forces alone.
    Trial bare;
    evaluateTrial(setup_, particles_, geometry_, from, false, a.snapBack, bare, nullptr, nullptr, a.keptStarts());
    if (bare.failed != SIZE_MAX) continue;
    const Eigen::VectorXd r = onUnknowns(geometry_.dofs, a.unknownReduction(), [&](std::int32_t c) { return a.external[c] - bare.internalForce[c]; });
    relative = r.norm() / std::max({a.external.norm(), bare.internalForce.norm(), 1e-300});
    if (relative <= kFinishFromRelative * settings_.tolerance) {
      Attempt b;
      if (attempt({}, &from, settings_.maxIterations, b)) {
        b.warmStart = nullptr;
        b.report.proximalSteps = k + 1;
        result = std::move(b);
        return true;
      }
    }
    if (a.report.iterations < settings_.hardIterations) alpha = std::max(smallest, 0.5 * alpha);
  }
  result.fail(kMaxProximalSteps, relative, NewtonFailure::NotConverged,
              "a stabilised step did not settle in " + std::to_string(kMaxProximalSteps) + " proximal steps");
  return false;
}

ImplicitStepReport ImplicitSolver::advance(const IndirectControl* control, double largest, double remaining) {
  ImplicitStepReport total;
  double& nextPiece = control ? nextOpening_ : nextPiece_;  // of pseudo-time, or of opening (mm)
  const double smallest = std::abs(largest) * std::ldexp(1.0, -settings_.maxHalvings);  // of the adaptive piece
  double piece = nextPiece > 0.0 ? std::clamp(nextPiece, smallest, std::abs(largest)) : std::abs(largest);
  piece = std::copysign(std::min(piece, std::abs(remaining)), largest);
  // The last piece before `remaining` ends takes what is left when that is at most 1.5 pieces.
  if (std::abs(remaining) <= 1.5 * std::abs(piece)) piece = remaining;
  // Attempts: the piece with the kept factorisation, then (if Newton did not converge) the same
  // piece factorising at every iteration, then halves of it, the last with 4 times the iterations.
  // A material snap-back under release: the band fails onto its stable branch wherever the piece's
  // converged state puts it past its limit, as in explicit runs, with no halving first. Under stop it
  // gets one halving and, if it persists, ends the run (docs/implicit.md, "Load steps").
  const bool release = setup_.scene.solver.snapBack == SnapBackPolicy::Release;
  bool retried = false;
  int snapBackCuts = 0;  // halvings because a point snapped back (stop): after the first, it persists
  int pathRedos = 0;     // tries of the same piece after its converged state grew the crack paths
  for (int cuts = 0;; ++cuts) {
    Attempt a;
    const bool finest = cuts >= settings_.maxHalvings;
    a.reuseRatio = cuts > 0 || retried ? 0.0 : settings_.reuseRatio;
    a.maxIterations = finest ? 4 * settings_.maxIterations : settings_.maxIterations;
    a.lastResort = finest;
    a.snapBack = release ? SnapBackPolicy::Release : SnapBackPolicy::Stop;
    a.keepReleases = finest && release;
    bool ok = solvePiece(control, piece, a);
    // A piece whose Newton (proper) stalls below the acceptance tolerance is kept: its residual
    // is carried into the next step's equilibrium (docs/implicit.md, "Load steps").
    bool relaxed = false;
    if (!ok && a.stalled && a.reuseRatio == 0.0 && a.failedResidual <= settings_.acceptTolerance) ok = relaxed = true;
    // A smallest piece that Newton cannot solve: stabilised (docs/implicit.md, "Stabilised steps").
    if (!ok && finest && !control && a.reason == NewtonFailure::NotConverged && settings_.stabilization > 0.0) {
      Attempt s;
      ok = solveStabilized(piece, s);  // a failure says why (its reason, residual and words)
      a = std::move(s);
    }
    // A piece that carries a point far past its onset is cut (docs/implicit.md, "Load steps").
    if (ok && !finest && a.trial.onsetOvershoot > settings_.onsetOvershoot)
      ok = a.fail(a.report.iterations, a.report.residual, NewtonFailure::OnsetOvershoot,
                  "a point passed its onset by " + std::to_string(a.trial.onsetOvershoot) + " of its strength");
    total.totalIterations += a.report.totalIterations;
    total.factorizations += a.report.factorizations;
    total.krylovIterations += a.report.krylovIterations;
    total.linearSolveSeconds += a.report.linearSolveSeconds;
    // Tracked crack paths: the converged state grows them (its new bands move the tips, its held
    // points start cracks); where that puts held points on a path, the piece is solved again with
    // the grown paths, so that a crack runs on within the step (docs/model.md, "Crack paths").
    if (ok && crackPaths_.tracked() && growCrackPaths(a.trial) > 0 && pathRedos < kMaxPathRedos) {
      ++pathRedos;
      --cuts;
      continue;
    }
    if (ok) {
      const double dashpotWork = commit(a, control ? 0.0 : piece);
      checkBalance();
      total.size = piece;
      total.cuts = cuts;
      total.iterations = a.report.iterations;
      total.residual = relaxed ? a.failedResidual : a.report.residual;
      total.relaxed = relaxed ? 1 : 0;
      total.released = a.releases();
      total.onsetOvershoot = a.trial.onsetOvershoot;
      total.proximalSteps = a.report.proximalSteps;
      total.dashpotWork = dashpotWork;
      // The next piece: longer after an easy step, shorter after a hard one.
      double grow = a.report.iterations <= settings_.easyIterations ? 2.0
                    : a.report.iterations >= settings_.hardIterations ? 0.5 : 1.0;
      if (a.trial.onsetOvershoot > 0.0)  // aim at 0.6 of the overshoot limit
        grow = std::min(grow, std::max(0.5, 0.6 * settings_.onsetOvershoot / a.trial.onsetOvershoot));
      nextPiece = std::abs(piece) * grow;
      return total;
    }
    if (!finest && !retried && cuts == 0 && a.reuseRatio > 0.0 && a.reason == NewtonFailure::NotConverged) {
      retried = true;  // the same piece with Newton proper
      --cuts;
      continue;
    }
    if (a.failedStatus == UpdateStatus::SnapBack) ++snapBackCuts;
    const bool persistingSnapBack = !release && snapBackCuts > 1 && a.failedStatus == UpdateStatus::SnapBack;
    if (!finest && !persistingSnapBack) {
      // The overshoot grows about linearly with the piece: cut to where it would meet the limit.
      const double overshootCut = a.trial.onsetOvershoot > settings_.onsetOvershoot && a.reason == NewtonFailure::OnsetOvershoot
                                      ? std::max(0.1, 0.8 * settings_.onsetOvershoot / a.trial.onsetOvershoot)
                                      : 0.5;
      piece *= std::min(0.5, overshootCut);
      continue;
    }
    std::ostringstream msg;
    msg << "implicit step " << steps_ + 1 << " (t = " << time_ << " s, load factor " << lambda_ << ", a piece of "
        << piece << " after " << cuts << " halvings): "
        << (persistingSnapBack ? "a material snap-back persists after a halving: " : "") << a.why << " at Newton iteration " << a.failedIteration
        << ", relative residual " << a.failedResidual;
    Vec2 where = Vec2::Zero();
    if (a.failedParticle != SIZE_MAX) {
      where = particles_.position[a.failedParticle];
      msg << "; particle " << a.failedParticle << " at (" << where[0] << ", " << where[1] << ") mm";
    }
    // Under displacement control without stabilised steps a cracked structure whose Newton fails on
    // the smallest piece has most likely passed a limit point: past a structural snap-back no state
    // of the structure near the last has the prescribed displacement (docs/implicit.md).
    const bool cracked = std::any_of(particles_.band.begin(), particles_.band.end(), [](std::int32_t b) { return b >= 0; }) ||
                         std::any_of(a.trial.band.begin(), a.trial.band.end(), [](const auto& b) { return b.has_value(); });
    const bool likelyLimitPoint = !control && cracked && settings_.stabilization == 0.0 &&
                                  (a.reason == NewtonFailure::NotConverged || a.reason == NewtonFailure::Singular);
    if (likelyLimitPoint)
      msg << ". The structure has most likely passed a limit point (a structural snap-back: past its peak the load and "
             "the displacement fall together), which displacement control cannot follow; indirect control "
             "(solver: {control: {indirect: ...}}, docs/implicit.md) traces it";
    const std::optional<std::size_t> particle =
        a.failedParticle == SIZE_MAX ? std::nullopt : std::optional<std::size_t>(a.failedParticle);
    SimulationError e(failureKindOf(a.reason, a.failedStatus), steps_ + 1, particle, where, msg.str(), a.failedStatus,
                      a.failedResidual);
    e.likelyLimitPoint = likelyLimitPoint;
    throw e;
  }
}

// A whole step of `size` in adaptive pieces: the reports summed.
ImplicitStepReport ImplicitSolver::stepInPieces(const IndirectControl* control, double size) {
  ImplicitStepReport total;
  double done = 0.0;
  while (std::abs(done) < std::abs(size) * (1.0 - 1e-12)) {
    const ImplicitStepReport r = advance(control, size, size - done);
    done += r.size;
    total.size += r.size;
    total.iterations = std::max(total.iterations, r.iterations);
    total.totalIterations += r.totalIterations;
    total.factorizations += r.factorizations;
    total.krylovIterations += r.krylovIterations;
    total.cuts += r.cuts;
    total.residual = std::max(total.residual, r.residual);
    total.released += r.released;
    total.relaxed += r.relaxed;
    total.linearSolveSeconds += r.linearSolveSeconds;
    total.onsetOvershoot = std::max(total.onsetOvershoot, r.onsetOvershoot);
    total.proximalSteps += r.proximalSteps;
    total.dashpotWork += r.dashpotWork;
  }
  return total;
}

ImplicitStepReport ImplicitSolver::advance(double largest, double remaining) { return advance(nullptr, largest, remaining); }

ImplicitStepReport ImplicitSolver::advance(const IndirectControl& control, double largest, double remaining) {
  return advance(&control, largest, remaining);
}

ImplicitStepReport ImplicitSolver::step(double dt) { return stepInPieces(nullptr, dt); }

ImplicitStepReport ImplicitSolver::step(const IndirectControl& control, double dTau) { return stepInPieces(&control, dTau); }

}  // namespace ecm::mpm
