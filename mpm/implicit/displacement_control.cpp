// Displacement control's Newton problem (mpm/implicit/displacement_control.hpp).
#include "mpm/implicit/displacement_control.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

namespace ecm::mpm {

Eigen::VectorXd DisplacementControl::residualOf(const Trial& t, double& relative) const {
  const Eigen::VectorXd r =
      onUnknowns(context_.geometry.dofs, a_.unknownReduction(), [&](std::int32_t c) { return a_.external[c] - t.internalForce[c]; });
  relative = r.norm() / std::max({a_.external.norm(), t.internalForce.norm(), 1e-300});
  return r;
}

void DisplacementControl::evaluate(const Eigen::VectorXd& du, Trial& t, const CycleGuard* cycle) const {
  evaluateTrial(context_.setup, context_.particles, context_.geometry, du, false, a_.snapBack, t, nullptr,
                cycle ? cycle->secantFlags() : nullptr, a_.keptStarts(), a_.dashpots);
}

// The predictor: linearised at the step's start (du = 0), loaded by the prescribed increments
// through the coupling K_fp: K_ff du_f = (f_ext - f_int)_f - (K du_p)_f. Starting Newton at the
// prescribed increments alone would strain the boundary's layer of particles with all of them.
// K_ff is the last factorisation while the unknowns are those it was made for.
bool DisplacementControl::start() {
  Attempt& a = a_;
  const StepContext& c = context_;
  const DofMap& dofs = c.geometry.dofs;
  const UnknownReduction* reduction = a.unknownReduction();
  const int n = reduction ? reduction->reduced() : dofs.unknowns();
  if (n > 0 || a.warmStart) {
    const Eigen::VectorXd prescribedIncrements = a.du;
    Trial start;
    evaluateTrial(c.setup, c.particles, c.geometry, Eigen::VectorXd::Zero(a.du.size()), false, a.snapBack, start, &prescribedIncrements, nullptr,
                  nullptr, a.dashpots);
    if (start.failed != SIZE_MAX) return a.failInMaterial(0, start, c.setup, c.particles);
    a.startForce = start.internalForce;
    if (a.warmStart) {  // a stabilised step's next alpha starts from the last one's solution
      a.du = *a.warmStart;
      evaluate(a.du, a.trial, nullptr);
      return true;
    }
    const Eigen::VectorXd rhs = onUnknowns(dofs, reduction, [&](std::int32_t k) {
      return a.external[k] - start.internalForce[k] - start.tangentTimesDirection[k];
    });
    if (!c.factors.isOf(c.factorKey) || a.reuseRatio <= 0.0) {
      assembleTangent(c.setup, c.particles, c.geometry, start);
      if (!c.factors.factorize(a.tangentOf(start), c.factorKey, dofs, reduction, a.report))
        return a.fail(0, 0.0, NewtonFailure::Singular, "the tangent at the step's start is singular");
    }
    const Eigen::VectorXd delta = c.factors.solve(rhs, a.report);
    if (!delta.allFinite()) return a.fail(0, 0.0, NewtonFailure::Singular, "the tangent at the step's start is singular");
    if (!reduction) {
      for (int u = 0; u < n; ++u) a.du[dofs.component[static_cast<std::size_t>(u)]] = delta[u];
    } else {  // a platen's or a tie's node components carry their prescribed increments already
      const Eigen::VectorXd onNodes = toUnknowns(reduction, delta);
      for (int u = 0; u < dofs.unknowns(); ++u) a.du[dofs.component[static_cast<std::size_t>(u)]] += onNodes[u];
    }
  }
  evaluate(a.du, a.trial, nullptr);
  // A predictor far past the onset limit is not worth converging: the piece is cut at once (not on
  // the last halving under release, which has no smaller piece to go to).
  const bool lastUnderRelease = a.lastResort && a.snapBack == SnapBackPolicy::Release;
  if (!lastUnderRelease && a.trial.failed == SIZE_MAX && a.trial.onsetOvershoot > 1.5 * c.settings.onsetOvershoot)
    return a.fail(0, 0.0, NewtonFailure::OnsetOvershoot,
                  "the predictor carried a point past its onset by " + std::to_string(a.trial.onsetOvershoot) + " of its strength");
  return true;
}

Residual DisplacementControl::residual(int) {
  Residual res;
  res.r = residualOf(a_.trial, res.relative);
  return res;
}

// Backtracking line search on |r|: the full step, then halves, the best kept.
void DisplacementControl::move(const Correction& d, const Residual& r, const CycleGuard& cycle) {
  Attempt& a = a_;
  const DofMap& dofs = context_.geometry.dofs;
  const Eigen::VectorXd delta = toUnknowns(a.unknownReduction(), d.step);
  Eigen::VectorXd full = Eigen::VectorXd::Zero(a.du.size());
  for (int u = 0; u < dofs.unknowns(); ++u) full[dofs.component[static_cast<std::size_t>(u)]] = delta[u];
  Trial best;
  double bestNorm = INFINITY, alpha = 1.0;
  Eigen::VectorXd bestDu;
  const double norm = r.r.norm();
  for (int tries = 0; tries < 6; ++tries, alpha *= 0.5) {
    Trial t;
    const Eigen::VectorXd du = a.du + alpha * full;
    evaluate(du, t, &cycle);
    if (t.failed != SIZE_MAX) continue;
    double rel = 0.0;
    const double tried = residualOf(t, rel).norm();
    if (tried < bestNorm) bestNorm = tried, best = std::move(t), bestDu = du;
    if (tried <= (1.0 - 1e-4 * alpha) * norm) break;
  }
  if (!std::isfinite(bestNorm)) {  // every length failed in the material: the full step's failure is reported
    evaluate(a.du + full, a.trial, &cycle);
    return;
  }
  a.du = std::move(bestDu);
  a.trial = std::move(best);
}

void DisplacementControl::backTo(const Iterate* best, const CycleGuard& cycle) {
  if (!best) return;
  a_.du = best->du;
  evaluate(a_.du, a_.trial, &cycle);
}

}  // namespace ecm::mpm
