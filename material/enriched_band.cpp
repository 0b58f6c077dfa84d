#include "material/enriched_band.hpp"

#include <cmath>
#include <sstream>

#include "material/driving_force.hpp"
#include "material/parameter_check.hpp"

namespace ecm {

namespace {

// Both eigenvalues of a 2x2 with positive real part: the traction-continuity system of Eq. (9)
// has a locally unique, stable solution branch.
bool positiveDefinite(const Mat2& k) { return k.determinant() > 0.0 && k.trace() > 0.0; }

}  // namespace

void EnrichedParams::validate() const {
  band.validate();
  requireInRange("band_width h (mm)", bandWidth, 0.0, 1e300);
}

EnrichedBand::EnrichedBand(const EnrichedParams& p)
    : law_((p.validate(), p.band)),
      bandWidth_(p.bandWidth),
      onsetBound_(0.5 * (law_.compliance()(0, 0) + std::abs(law_.compliance()(0, 1)))) {}

double EnrichedBand::intactDrivingForce(const Voigt& strain) const {
  return drivingForce(stiffness() * strain, law_.compliance()).value;
}

std::optional<double> EnrichedBand::onsetFraction(const Voigt& strain, const Voigt& increment) const {
  const double yOnset = law_.onsetDrivingForce();
  auto excess = [&](double a) { return intactDrivingForce(strain + a * increment) - yOnset; };
  double gb = excess(1.0);
  if (gb < 0.0) return std::nullopt;
  double ga = excess(0.0);
  if (ga >= 0.0) return 0.0;
  // Illinois regula falsi on the piecewise-quadratic Y(alpha) (MODEL-NOTES pitfall 1).
  double a = 0.0, b = 1.0;
  int side = 0;
  for (int it = 0; it < 200 && b - a > 1e-15; ++it) {
    const double c = (a * gb - b * ga) / (gb - ga);
    const double gc = excess(c);
    if (std::abs(gc) <= 1e-15 * yOnset) return c;
    if (gc < 0.0) {
      a = c, ga = gc;
      if (side == -1) gb *= 0.5;
      side = -1;
    } else {
      b = c, gb = gc;
      if (side == +1) ga *= 0.5;
      side = +1;
    }
  }
  return b;  // the end of the bracket at which the criterion is met
}

BandEquilibrium EnrichedBand::equilibrium(const BandState& b, const BandDamageLaw::LoadingSurface& surface,
                                          const Voigt& strain, const Vec2& jump, bool loadingTangent) const {
  const JumpMap n = jumpToStrain(b.crackNormal);
  const double f = b.volumeFraction;
  BandEquilibrium eq;
  eq.bandStrain = b.onsetStrain + n * jump / bandWidth_;                  // Eq. (3)
  eq.band = law_.evaluate(surface, eq.bandStrain, loadingTangent);        // Eqs. (5), (11)-(13)
  eq.stress = stiffness() * (strain - f * eq.bandStrain) / (1.0 - f);    // Eqs. (2), (4)
  eq.residual = n.transpose() * (eq.stress - eq.band.stress);            // Eq. (6)
  eq.jacobian = n.transpose() * (f / (1.0 - f) * stiffness() + eq.band.tangent) * n / bandWidth_;  // Eq. (9)
  return eq;
}

Tangent EnrichedBand::consistentTangent(const BandState& b, const BandEquilibrium& eq) const {
  const JumpMap n = jumpToStrain(b.crackNormal);
  const double f = b.volumeFraction;
  const Tangent& a = stiffness();
  const Eigen::Matrix<double, 2, 3> dJumpdStrain = eq.jacobian.inverse() * n.transpose() * a / (1.0 - f);  // Eq. (8)
  return a / (1.0 - f) * (Tangent::Identity() - f / bandWidth_ * n * dJumpdStrain);                      // Eq. (10)
}

UpdateResult EnrichedBand::updateCracked(BandState& b, Voigt& strain, const Voigt& increment) const {
  const Voigt eps = strain + increment;
  const JumpMap n = jumpToStrain(b.crackNormal);
  UpdateResult res;
  Vec2 jump = b.jump;
  const BandDamageLaw::LoadingSurface surface = law_.loadingSurface(b.integrity);
  BandEquilibrium eq = equilibrium(b, surface, eps, jump, true);
  // Relative to f_t'; at enormous strains the floor is the round-off of a : eps itself.
  const double tol = kRelativeTolerance * tensileStrength() + kRoundOff * (stiffness() * eps).norm();
  double rn = eq.residual.norm();
  const bool startsOnSurface = eq.band.drivingForce >= surface.threshold * (1.0 - 1e-12) &&
                               eq.band.drivingForce > 0.0;
  int it = 0;
  bool sawUnstableBranch = false;
  for (; rn > tol && it < kMaxIterations; ++it) {
    Vec2 step = eq.jacobian.partialPivLu().solve(eq.residual);
    if (it == 0 && startsOnSurface) {
      // At [u] = [u]_old the band sits on its loading surface (MODEL-NOTES pitfall 2): take the
      // loading tangent if its step does load the band, the secant one if its step unloads it.
      // If neither is consistent the loading branch has turned back: a snap-back.
      const auto rate = [&](const Vec2& s) { return eq.band.drivingForceRate.dot(n * s); };
      const bool loadingOk = positiveDefinite(eq.jacobian) && rate(step) >= 0.0;
      if (!loadingOk) {
        const Mat2 secant = n.transpose() * (b.volumeFraction / (1.0 - b.volumeFraction) * stiffness() +
                                             b.integrity * stiffness()) * n / bandWidth_;
        const Vec2 secantStep = secant.partialPivLu().solve(eq.residual);
        if (rate(secantStep) <= 0.0) {
          step = secantStep;
        } else if (!positiveDefinite(eq.jacobian)) {
          res.status = UpdateStatus::SnapBack;
          res.residual = rn;
          res.iterations = it;
          res.stress = eq.stress;
          return res;
        }
      }
    }
    if (!step.allFinite()) break;
    double alpha = 1.0;
    BandEquilibrium trial;
    for (int ls = 0; ls < 40; ++ls, alpha *= 0.5) {
      trial = equilibrium(b, surface, eps, jump + alpha * step, true);
      if (trial.residual.norm() < (1.0 - 1e-4 * alpha) * rn) break;
    }
    jump += alpha * step;
    eq = trial;
    rn = eq.residual.norm();
    sawUnstableBranch = sawUnstableBranch || (eq.band.loading && !positiveDefinite(eq.jacobian));
  }
  res.residual = rn;
  res.iterations = it;
  res.stress = eq.stress;
  if (!(rn <= tol)) {
    // Newton that wandered through loading states with C of Eq. (9) not positive was looking
    // for a branch that does not continue: that is a snap-back, not a numerical failure.
    res.status = sawUnstableBranch ? UpdateStatus::SnapBack : UpdateStatus::NotConverged;
    return res;
  }
  if (it > 0 && eq.band.loading && !positiveDefinite(eq.jacobian)) {
    res.status = UpdateStatus::SnapBack;  // Newton drifted onto a branch strain control cannot reach
    return res;
  }
  // A large loading increment may have jumped over a snap-back: the branch between the two
  // converged states must stay stable (C of Eq. (9) positive) all along, checked at samples.
  if (eq.band.loading && (jump - b.jump).norm() > kJumpCheck * bandWidth_) {
    for (int k = 1; k < kJumpSamples; ++k) {
      const BandEquilibrium mid = equilibrium(b, surface, eps, b.jump + (double(k) / kJumpSamples) * (jump - b.jump), true);
      if (mid.band.loading && !positiveDefinite(mid.jacobian)) {
        res.status = UpdateStatus::SnapBack;
        return res;
      }
    }
  }
  res.tangent = consistentTangent(b, eq);
  res.dissipation = b.volumeFraction * law_.dissipation(b.integrity, eq.band.integrity);  // f int Y dD
  b.jump = jump;
  b.integrity = eq.band.integrity;
  strain = eps;
  return res;
}

UpdateResult EnrichedBand::updateIntactSlow(Voigt& strain, const Voigt& increment, const EffectiveSize& size,
                                            std::optional<BandState>& onset) const {
  UpdateResult r;
  r.stress = stiffness() * (strain + increment);
  r.tangent = stiffness();
  const std::optional<double> alpha = onsetFraction(strain, increment);
  if (!alpha) {
    strain += increment;
    return r;
  }
  BandState b;
  b.onsetStrain = strain + *alpha * increment;
  b.crackNormal = canonicalNormal(principalStresses(stiffness() * b.onsetStrain).firstDirection);
  const double effectiveSize = size(b.crackNormal);
  if (!(effectiveSize > bandWidth_)) {
    std::ostringstream msg;
    msg << "effective size H = " << effectiveSize << " mm must exceed the band width h = " << bandWidth_ << " mm";
    throw ParameterError(msg.str());
  }
  b.volumeFraction = bandWidth_ / effectiveSize;  // Eq. (1)
  Voigt cracked = b.onsetStrain;
  r = updateCracked(b, cracked, (1.0 - *alpha) * increment);
  if (r.converged()) {
    strain = cracked;
    onset = b;
  }
  return r;
}

UpdateResult EnrichedBand::update(EnrichedState& state, const Voigt& increment, const EffectiveSize& size) const {
  if (state.band) return updateCracked(*state.band, state.strain, increment);
  return updateIntact(state.strain, increment, size, state.band);
}

}  // namespace ecm
