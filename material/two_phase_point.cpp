#include "material/two_phase_point.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <vector>

#include "material/driving_force.hpp"
#include "material/parameter_check.hpp"
#include "material/release_scan.hpp"

namespace ecm {

namespace {

// Both eigenvalues of a 2x2 with positive real part: the traction-continuity system of Eq. (9)
// has a locally unique, stable solution branch.
bool positiveDefinite(const Mat2& k) { return k.determinant() > 0.0 && k.trace() > 0.0; }

// The smaller real part of the eigenvalues of K (Eq. (9)): positive exactly where
// positiveDefinite() holds, and continuous, so it can be minimised along a path.
double smallestRealEigenvalue(const Mat2& k) {
  const double half = 0.5 * k.trace();
  const double disc = half * half - k.determinant();
  return disc > 0.0 ? half - std::sqrt(disc) : half;
}

}  // namespace

std::string effectiveSizeProblem(double effectiveSize, double bandWidth, int bands) {
  if (effectiveSize >= minimumEffectiveSize(bandWidth, bands)) return "";
  std::ostringstream msg;
  msg.precision(10);
  msg << "H = " << effectiveSize << " mm is below the smallest effective size " << (bands > 1 ? "2 h" : "h") << " (1 + "
      << kMinimumSizeMargin << ") = " << minimumEffectiveSize(bandWidth, bands) << " mm for the band width h = "
      << bandWidth << " mm: a bulk thinner than that (1 - "
      << (bands > 1 ? "f1 - f2" : "f") << " < 1e-6, Eq. (1)) leaves its stress to round-off";
  if (bands > 1) msg << " (second_band: orthogonal needs room for two bands)";
  msg << " (docs/model.md)";
  return msg.str();
}

const char* toString(SecondBandOption o) { return o == SecondBandOption::Orthogonal ? "orthogonal" : "off"; }

void EnrichedParams::validate() const {
  band.validate();
  requireInRange("band_width h (mm)", bandWidth, 0.0, 1e300);
}

TwoPhasePoint::TwoPhasePoint(const EnrichedParams& p)
    : law_((p.validate(), p.band)),
      bandWidth_(p.bandWidth),
      onsetBound_(law_.drivingForceBound()),
      shearModulus_(law_.stiffness()(2, 2)),
      acousticRatio_((law_.stiffness()(0, 1) + law_.stiffness()(2, 2)) / law_.stiffness()(0, 0)),
      secondBand_(p.secondBand),
      secondOnsetStress_(std::sqrt(2.0 * law_.onsetDrivingForce() / law_.compliance()(0, 0))) {}

double TwoPhasePoint::intactDrivingForce(const Voigt& strain) const {
  return law_.drivingForceValue(stiffness() * strain);  // bitwise drivingForce().value
}

std::optional<double> TwoPhasePoint::onsetFraction(const Voigt& strain, const Voigt& increment) const {
  return law_.onsetFraction(strain, increment);
}

BandEquilibrium TwoPhasePoint::equilibrium(const BandState& b, const BandDamageLaw::LoadingSurface& surface,
                                          const Voigt& strain, const Vec2& jump, bool loadingTangent) const {
  const JumpMap N = jumpToStrain(b.crackNormal);
  const double f = b.volumeFraction;
  BandEquilibrium eq;
  eq.bandStrain = b.onsetStrain + N * jump / bandWidth_;                  // Eq. (3)
  eq.band = law_.evaluate(surface, eq.bandStrain, loadingTangent);        // Eqs. (5), (11)-(13)
  eq.stress = stiffness() * (strain - f * eq.bandStrain) / (1.0 - f);    // Eqs. (2), (4)
  eq.residual = N.transpose() * (eq.stress - eq.band.stress);            // Eq. (6)
  eq.jacobian = N.transpose() * (f / (1.0 - f) * stiffness() + eq.band.tangent) * N / bandWidth_;  // Eq. (9)
  return eq;
}

Mat2 TwoPhasePoint::secantJacobian(const BandState& b, double x) const {
  const JumpMap N = jumpToStrain(b.crackNormal);
  const double f = b.volumeFraction;
  return N.transpose() * ((f / (1.0 - f) + x) * stiffness()) * N / bandWidth_;  // Eq. (9), a_L = x a
}

Tangent TwoPhasePoint::consistentTangent(const BandState& b, const Mat2& jacobian) const {
  const JumpMap N = jumpToStrain(b.crackNormal);
  const double f = b.volumeFraction;
  const Tangent& a = stiffness();
  const Eigen::Matrix<double, 2, 3> dJumpdStrain = jacobian.inverse() * N.transpose() * a / (1.0 - f);  // Eq. (8)
  return a / (1.0 - f) * (Tangent::Identity() - f / bandWidth_ * N * dJumpdStrain);                      // Eq. (10)
}

UpdateResult TwoPhasePoint::updateCracked(BandState& b, Voigt& strain, const Voigt& increment,
                                         UpdateOptions options) const {
  UpdateResult r = predictCorrect(b, strain, increment, options.tangent, options.stressControlled);
  if (r.converged() || options.snapBack != SnapBackPolicy::Release) return r;
  if (r.status == UpdateStatus::SnapBack) return releaseSnapBack(b, strain, increment, options.tangent);
  // Newton on the envelope can stall without meeting an unstable state it could name: where the
  // nearest consistent state lies a damage jump away (a nearly intact band, Y with the kink of
  // Eq. (12) as a principal stress crosses zero). The release's scan in x finds that state; if
  // it finds none, the stall is reported as it was.
  const UpdateResult released = releaseSnapBack(b, strain, increment, options.tangent);
  return released.converged() ? released : r;
}

UpdateResult TwoPhasePoint::releaseSnapBack(BandState& b, Voigt& strain, const Voigt& increment, bool tangent) const {
  const Voigt eps = strain + increment;
  const double f = b.volumeFraction;
  // With the damage frozen at x, Eq. (6) is linear in [u] (secant K of Eq. (9)): [u](x) in one
  // solve. The band is in equilibrium with consistent damage where g(x) = Y([u](x)) - F(x) = 0.
  // g > 0 at x0 (the band must load); g -> -inf as x -> 0 (material/release_scan.hpp).
  struct Probe {
    double g;
    BandState band;
  };
  const auto probe = [&](double x) {
    Probe p{0.0, b};
    p.band.integrity = x;
    const BandDamageLaw::LoadingSurface frozen{x, std::numeric_limits<double>::infinity()};
    const BandEquilibrium eq = equilibrium(p.band, frozen, eps, b.jump, false);
    p.band.jump = b.jump + secantJacobian(b, x).llt().solve(eq.residual);
    const BandEquilibrium moved = equilibrium(p.band, frozen, eps, p.band.jump, false);
    p.g = moved.band.drivingForce / damageFunction(law_.law(), x) - 1.0;
    return p;
  };
  UpdateResult res;
  res.status = UpdateStatus::SnapBack;
  // Polish each root with the regular update at zero increment: it confirms continuity, loading
  // consistency and stability (K of Eq. (9) positive), or reports this root unstable.
  releaseScan(probe, b.integrity, res.iterations, [&](const Probe& root) {
    BandState trial = root.band;
    Voigt s = eps;
    const UpdateResult r = predictCorrect(trial, s, Voigt::Zero(), tangent);
    const bool isStable = r.converged() && positiveDefinite(equilibrium(trial, law_.envelope(trial.integrity), eps, trial.jump, true).jacobian);
    if (!isStable) return false;
    res = r;
    res.iterations += r.iterations;
    res.released = true;
    res.dissipation = f * law_.dissipation(b.integrity, trial.integrity);  // f int Y dD over the release
    b = trial;
    strain = eps;
    return true;
  });
  return res;
}

// Relative to f_t'; at enormous strains the floor is the round-off of a : eps itself, or of
// f a eps_L / (1 - f) in the bulk stress of Eq. (4), which is larger once f > 1/2 (f near 1,
// docs/model.md).
double TwoPhasePoint::crackedTolerance(const Voigt& aEps, double f) const {
  return kRelativeTolerance * tensileStrength() + kRoundOff * aEps.norm() * std::max(1.0, f / (1.0 - f));
}

UpdateResult TwoPhasePoint::predictCorrect(BandState& b, Voigt& strain, const Voigt& increment, bool tangent,
                                          unsigned stressControlled) const {
  const Voigt eps = strain + increment;
  UpdateResult res;
  const Voigt aEps = stiffness() * eps;
  const double f = b.volumeFraction;
  const double tol = crackedTolerance(aEps, f);

  // 1. Elastic predictor: with the band's damage frozen, Eq. (6) is linear in [u] and the secant
  //    K of Eq. (9) (a_L = x0 a, always positive definite) solves it in one step. If the band
  //    stays inside its loading surface, that is the answer (unloading or neutral loading):
  //    most cracked updates of a structure end here, without the damage law or its tangent.
  const JumpMap N = jumpToStrain(b.crackNormal);
  const double x0 = b.integrity;
  Vec2 jump = b.jump;
  Voigt aBand = stiffness() * (b.onsetStrain + N * jump / bandWidth_);            // a eps_L, Eq. (3)
  const auto stressOf = [&](const Voigt& aL) -> Voigt { return (aEps - f * aL) / (1.0 - f); };  // Eqs. (2), (4)
  Vec2 residual = N.transpose() * (stressOf(aBand) - x0 * aBand);                  // Eqs. (6), (11)
  for (int it = 0; it < 3 && residual.norm() > tol; ++it) {  // 1 step + round-off
    jump += secantSolve(b, x0, residual);
    aBand = stiffness() * (b.onsetStrain + N * jump / bandWidth_);
    residual = N.transpose() * (stressOf(aBand) - x0 * aBand);
    ++res.iterations;
  }
  // The loading surface F(x0) >= F(1): a band whose Y is below onset (a closed or barely open
  // crack) is unloading without evaluating F (a pow).
  const double y = law_.drivingForceValue(aBand);
  const bool belowOnset = y <= law_.onsetDrivingForce();
  const BandDamageLaw::LoadingSurface surface =
      belowOnset ? BandDamageLaw::LoadingSurface{x0, law_.onsetDrivingForce()} : law_.loadingSurface(x0);
  if (y <= surface.threshold) {
    res.residual = residual.norm();
    res.stress = stressOf(aBand);
    if (!(res.residual <= tol)) {
      res.status = UpdateStatus::NotConverged;
      return res;
    }
    if (tangent) res.tangent = consistentTangent(b, secantJacobian(b, x0));
    b.jump = jump;
    strain = eps;
    return res;
  }

  // 2. Damage corrector: Newton with line search on the monotonic loading envelope, smooth across
  //    the loading surface (docs/model.md pitfall 2: no loading/unloading kink inside the
  //    iteration), from the predictor's [u] with the loading tangent. The root must load the band
  //    (x <= x0) on a stable branch (K of Eq. (9) positive definite); otherwise the loading
  //    branch has turned back under strain control: a snap-back.
  const BandDamageLaw::LoadingSurface envelope = BandDamageLaw::envelope(surface);
  // Newton starts from the predictor's jump: the root lies a damage increment beyond it.
  BandEquilibrium eq = equilibrium(b, envelope, eps, jump, true);
  double rn = eq.residual.norm();
  bool sawUnstableBranch = false;
  int it = 0;
  for (; rn > tol && it < kMaxIterations; ++it) {
    const Vec2 step = eq.jacobian.partialPivLu().solve(eq.residual);
    if (!step.allFinite()) break;
    double alpha = 1.0;
    BandEquilibrium trial;
    for (int ls = 0; ls < 40; ++ls, alpha *= 0.5) {
      trial = equilibrium(b, envelope, eps, jump + alpha * step, true);
      if (trial.residual.norm() < (1.0 - 1e-4 * alpha) * rn) break;
    }
    jump += alpha * step;
    eq = trial;
    rn = eq.residual.norm();
    sawUnstableBranch = sawUnstableBranch || (eq.band.loading && !positiveDefinite(eq.jacobian));
  }
  res.iterations += it;
  res.residual = rn;
  res.stress = eq.stress;
  if (!(rn <= tol)) {
    // Newton that wandered through loading states with K of Eq. (9) not positive was looking
    // for a branch that does not continue: that is a snap-back, not a numerical failure.
    res.status = sawUnstableBranch ? UpdateStatus::SnapBack : UpdateStatus::NotConverged;
    return res;
  }
  if (eq.band.integrity >= b.integrity) {
    // The envelope's root lies below the loading surface, where the elastic predictor found no
    // solution either: by round-off only (neutral loading, accept with the damage unchanged),
    // or the loading branch has turned back under strain control.
    if (eq.band.drivingForce < surface.threshold * (1.0 - kNeutralLoading)) {
      res.status = UpdateStatus::SnapBack;
      return res;
    }
    eq = equilibrium(b, surface, eps, jump, false);  // neutral: the secant K, damage unchanged
  } else if (stressControlled == 0 ? !positiveDefinite(eq.jacobian)
                                    : !(stabilityMargins(b, eq.jacobian, stressControlled).minCoeff() > -kMarginFloor)) {
    res.status = UpdateStatus::SnapBack;  // a root on the unstable branch
    return res;
  }
  // The root is stable; the path to it must be too (docs/model.md, "Snap-back on the path"): a
  // loading increment whose jump is longer than kJumpCheck h may have passed a limit point.
  if ((jump - b.jump).norm() > kJumpCheck * bandWidth_ && !bandHasFailed(b) &&
      firstUnstableOnPath(b, surface, jump, stressControlled)) {
    res.status = UpdateStatus::SnapBack;
    return res;
  }
  return finishUpdate(b, strain, eps, jump, eq, surface.threshold, tol, tangent, res);
}

Vec2 TwoPhasePoint::stabilityMargins(const BandState& b, const Mat2& jacobian, unsigned stressControlled) const {
  // K scaled by its intact secant value mu (f / (1 - f) + 1) / h.
  const double kMargin =
      smallestRealEigenvalue(jacobian) * bandWidth_ / (shearModulus_ * (b.volumeFraction / (1.0 - b.volumeFraction) + 1.0));
  if (stressControlled == 0 || !(kMargin > 0.0)) return {kMargin, 1.0};
  // Mixed control: the Jacobian of (jump, stress-controlled strains) has det K det D_ss
  // (Schur complement, D of Eq. (10)); D_ss scaled by E.
  return {kMargin, stressControlledMargin(consistentTangent(b, jacobian), stressControlled)};
}

double TwoPhasePoint::stressControlledMargin(const Tangent& d, unsigned stressControlled) const {
  int idx[3], m = 0;
  for (int i = 0; i < 3; ++i)
    if (stressControlled & (1u << i)) idx[m++] = i;
  double dMargin = 0.0;
  if (m == 1) {
    dMargin = d(idx[0], idx[0]);
  } else if (m == 2) {
    Mat2 block;
    block << d(idx[0], idx[0]), d(idx[0], idx[1]), d(idx[1], idx[0]), d(idx[1], idx[1]);
    dMargin = smallestRealEigenvalue(block);
  } else {
    dMargin = d.eigenvalues().real().minCoeff();
  }
  return dMargin / law_.law().youngsModulus;
}

bool TwoPhasePoint::bandHasFailed(const BandState& b) const {
  const JumpMap N = jumpToStrain(b.crackNormal);
  const Vec2 traction = b.integrity * (N.transpose() * (stiffness() * (b.onsetStrain + N * b.jump / bandWidth_)));  // Eq. (11)
  return traction.norm() < kFailedTraction * tensileStrength();
}

Mat2 TwoPhasePoint::loadingJacobian(const BandState& b, const BandDamageLaw::LoadingSurface& surface, const Vec2& jump) const {
  const JumpMap N = jumpToStrain(b.crackNormal);
  const BandResponse band = law_.evaluate(surface, b.onsetStrain + N * jump / bandWidth_, true);  // Eq. (3)
  return N.transpose() * (b.volumeFraction / (1.0 - b.volumeFraction) * stiffness() + band.tangent) * N / bandWidth_;  // Eq. (9)
}

std::optional<double> TwoPhasePoint::firstUnstableOnPath(const BandState& b, const BandDamageLaw::LoadingSurface& surface,
                                                        const Vec2& jump, unsigned stressControlled) const {
  // States along the straight jump segment from the converged state b to `jump`, the band on
  // its loading surface (elastic inside it, loading beyond it): the equilibrium path itself
  // when the sliding jump does not change. K of Eq. (9) and D of Eq. (10) depend on the jump only.
  const Vec2 delta = jump - b.jump;
  const auto margins = [&](double t) {
    return stabilityMargins(b, loadingJacobian(b, surface, b.jump + t * delta), stressControlled);
  };
  // The first zero of margin i between a stable fraction and an unstable one (bisection).
  const auto crossing = [&](int i, double stable, double unstable) {
    for (int it = 0; it < 50 && unstable - stable > 1e-14; ++it) {
      const double mid = 0.5 * (stable + unstable);
      (margins(mid)[i] > -kMarginFloor ? stable : unstable) = mid;
    }
    return unstable;
  };
  // Samples: every kJumpCheck h (at least kJumpSamples, at most kMaxPathSamples), and
  // geometrically closer towards the start, where the softening branch turns fastest.
  const double length = delta.norm();
  // (Clamped as a double before the cast: a huge jump's count does not fit an int; NaN gives the fewest.)
  const int uniform = static_cast<int>(std::fmin(
      std::fmax(std::ceil(length / (kJumpCheck * bandWidth_)), double(kJumpSamples)), double(kMaxPathSamples)));
  std::vector<double> ts;
  ts.reserve(uniform + 400);
  for (int k = 0; k <= uniform; ++k) ts.push_back(double(k) / uniform);
  for (double t = kFirstGeometricSample; t < 1.0 / uniform; t *= kGeometricRatio) ts.push_back(t);
  std::sort(ts.begin(), ts.end());
  const int count = static_cast<int>(ts.size());
  std::vector<Vec2> sampled(count);
  for (int k = 0; k < count; ++k) {
    sampled[k] = margins(ts[k]);
    for (int i = 0; i < 2; ++i)
      if (!(sampled[k][i] > -kMarginFloor)) return k == 0 ? 0.0 : crossing(i, ts[k - 1], ts[k]);
  }
  // An unstable stretch narrower than the sampling lies next to a local minimum of its margin
  // among the samples: golden-section search around the smallest few of them.
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  std::optional<double> first;
  for (int i = 0; i < (stressControlled ? 2 : 1); ++i) {
    std::vector<int> minima;
    for (int k = 0; k < count; ++k)
      if ((k == 0 || sampled[k][i] <= sampled[k - 1][i]) && (k + 1 == count || sampled[k][i] <= sampled[k + 1][i]))
        minima.push_back(k);
    std::sort(minima.begin(), minima.end(), [&](int a, int b) { return sampled[a][i] < sampled[b][i]; });
    if (minima.size() > kRefinedMinima) minima.resize(kRefinedMinima);
    const auto margin = [&](double t) { return margins(t)[i]; };
    for (int k : minima) {
      const double left = ts[std::max(0, k - 1)];
      double lo = left, hi = ts[std::min(count - 1, k + 1)];
      double t1 = hi - g * (hi - lo), t2 = lo + g * (hi - lo), m1 = margin(t1), m2 = margin(t2);
      for (int it = 0; it < 50 && hi - lo > 1e-12 * (ts[std::min(count - 1, k + 1)] - left); ++it) {
        if (!(m1 > -kMarginFloor) || !(m2 > -kMarginFloor)) {
          const double t = crossing(i, left, !(m1 > -kMarginFloor) ? t1 : t2);
          first = first ? std::min(*first, t) : t;
          break;
        }
        if (m1 < m2) {
          hi = t2, t2 = t1, m2 = m1, t1 = hi - g * (hi - lo), m1 = margin(t1);
        } else {
          lo = t1, t1 = t2, m1 = m2, t2 = lo + g * (hi - lo), m2 = margin(t2);
        }
      }
    }
  }
  return first;
}

UpdateResult TwoPhasePoint::finishUpdate(BandState& b, Voigt& strain, const Voigt& eps, const Vec2& jump,
                                        const BandEquilibrium& eq, double thresholdOld, double tol, bool tangent,
                                        UpdateResult& res) const {
  res.residual = eq.residual.norm();
  res.stress = eq.stress;
  if (!(res.residual <= tol)) {
    res.status = UpdateStatus::NotConverged;
    return res;
  }
  res.status = UpdateStatus::Converged;
  if (tangent) res.tangent = consistentTangent(b, eq);
  // f int Y dD; on the loading branch F(x_new) = Y
  res.dissipation = b.volumeFraction * law_.dissipation(b.integrity, eq.band.integrity, thresholdOld, eq.band.drivingForce);
  b.jump = jump;
  b.integrity = eq.band.integrity;
  strain = eps;
  return res;
}

UpdateResult TwoPhasePoint::updateIntactSlow(Voigt& strain, const Voigt& increment, const EffectiveSize& size,
                                            std::optional<BandState>& onset, UpdateOptions options,
                                            std::optional<BandState>* secondOnset) const {
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
  b.crackNormal = options.onsetNormal ? canonicalNormal(*options.onsetNormal)
                                      : canonicalNormal(principalStresses(stiffness() * b.onsetStrain).firstDirection);
  const double effectiveSize = size(b.crackNormal);
  if (!(effectiveSize >= minimumEffectiveSize(bandWidth_))) {  // H <= h leaves no bulk (docs/model.md)
    r.status = UpdateStatus::SizeTooSmall;
    r.refusedSize = effectiveSize;
    return r;
  }
  b.volumeFraction = bandWidth_ / effectiveSize;  // Eq. (1)
  Voigt cracked = b.onsetStrain;
  r = secondOnset ? updateCracked(b, nullptr, cracked, (1.0 - *alpha) * increment, size, *secondOnset, options)
                  : updateCracked(b, cracked, (1.0 - *alpha) * increment, options);
  if (r.converged()) {
    strain = cracked;
    onset = b;
  }
  return r;
}

UpdateResult TwoPhasePoint::update(EnrichedState& state, const Voigt& increment, const EffectiveSize& size,
                                   UpdateOptions options) const {
  if (!opensSecondBand()) {
    if (state.band) return updateCracked(*state.band, state.strain, increment, options);
    return updateIntact(state.strain, increment, size, state.band, options);
  }
  if (state.band) {
    std::optional<BandState> second;
    const UpdateResult r = updateCracked(*state.band, state.secondBand ? &*state.secondBand : nullptr, state.strain,
                                         increment, size, second, options);
    if (second) state.secondBand = second;
    return r;
  }
  return updateIntact(state.strain, increment, size, state.band, state.secondBand, options);
}

}  // namespace ecm
