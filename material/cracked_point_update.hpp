#pragma once
// The members of CrackedPoint (material/cracked_point.hpp): the cracked update of an enriched
// point, once for plane and space. Included by the two points' .cpp files, which instantiate it.
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "material/cracked_point.hpp"
#include "material/jump_stability.hpp"
#include "material/release_scan.hpp"
#include "material/two_phase_point.hpp"

namespace ecm {

namespace cracked {
using Limits = TwoPhasePoint;  // the update's tolerances and sample counts (kMaxIterations, ...)
}  // namespace cracked

// Relative to f_t'; at enormous strains the floor is the round-off of a : eps itself, or of
// f a eps_L / (1 - f) in the bulk stress of Eq. (4), which is larger once f > 1/2 (f near 1,
// docs/model.md).
template <class Space, class Point>
double CrackedPoint<Space, Point>::crackedTolerance(const Strain& aEps, double f) const {
  return cracked::Limits::kRelativeTolerance * self().tensileStrength() + cracked::Limits::kRoundOff * aEps.norm() * std::max(1.0, f / (1.0 - f));
}

template <class Space, class Point>
std::optional<typename CrackedPoint<Space, Point>::Band> CrackedPoint<Space, Point>::bandAtOnset(
    const Strain& onsetStrain, const Jump& normal, double effectiveSize, Result& refused) const {
  const double h = self().bandWidth();
  if (!(effectiveSize >= minimumEffectiveSize(h))) {  // H <= h leaves no bulk (docs/model.md)
    refused.status = UpdateStatus::SizeTooSmall;
    refused.refusedSize = effectiveSize;
    return std::nullopt;
  }
  Band b;
  b.onsetStrain = onsetStrain;
  b.crackNormal = normal;
  b.volumeFraction = h / effectiveSize;  // Eq. (1)
  return b;
}

template <class Space, class Point>
typename CrackedPoint<Space, Point>::Equilibrium CrackedPoint<Space, Point>::equilibrium(const Band& b, const LoadingSurface& surface, const Strain& strain,
                                                                          const Jump& jump, bool loadingTangent) const {
  const Point& p = self();
  const JumpMap N = Space::jumpMap(b.crackNormal);
  const double f = b.volumeFraction;
  Equilibrium eq;
  eq.bandStrain = b.onsetStrain + N * jump / p.bandWidth();                                   // Eq. (3)
  eq.band = p.evaluateBand(surface, eq.bandStrain, loadingTangent);                           // Eqs. (5), (11)-(13)
  eq.stress = p.stiffness() * (strain - f * eq.bandStrain) / (1.0 - f);                       // Eqs. (2), (4)
  eq.residual = N.transpose() * (eq.stress - eq.band.stress);                                 // Eq. (6)
  eq.jacobian = N.transpose() * (f / (1.0 - f) * p.stiffness() + eq.band.tangent) * N / p.bandWidth();  // Eq. (9)
  return eq;
}

template <class Space, class Point>
typename CrackedPoint<Space, Point>::JumpJacobian CrackedPoint<Space, Point>::secantJacobian(const Band& b, double x) const {
  const Point& p = self();
  const JumpMap N = Space::jumpMap(b.crackNormal);
  const double f = b.volumeFraction;
  return N.transpose() * ((f / (1.0 - f) + x) * p.stiffness()) * N / p.bandWidth();  // Eq. (9), a_L = x a
}

template <class Space, class Point>
typename CrackedPoint<Space, Point>::JumpJacobian CrackedPoint<Space, Point>::loadingJacobian(const Band& b, const LoadingSurface& surface,
                                                                               const Jump& jump) const {
  const Point& p = self();
  const JumpMap N = Space::jumpMap(b.crackNormal);
  const auto band = p.evaluateBand(surface, b.onsetStrain + N * jump / p.bandWidth(), true);  // Eq. (3)
  return N.transpose() * (b.volumeFraction / (1.0 - b.volumeFraction) * p.stiffness() + band.tangent) * N / p.bandWidth();  // Eq. (9)
}

template <class Space, class Point>
typename CrackedPoint<Space, Point>::StrainTangent CrackedPoint<Space, Point>::consistentTangent(const Band& b, const JumpJacobian& jacobian) const {
  const Point& p = self();
  const JumpMap N = Space::jumpMap(b.crackNormal);
  const double f = b.volumeFraction;
  const StrainTangent& a = p.stiffness();
  const Eigen::Matrix<double, Jump::RowsAtCompileTime, StrainTangent::RowsAtCompileTime> dJumpdStrain =
      jacobian.inverse() * N.transpose() * a / (1.0 - f);                                        // Eq. (8)
  return a / (1.0 - f) * (StrainTangent::Identity() - f / p.bandWidth() * N * dJumpdStrain);  // Eq. (10)
}

template <class Space, class Point>
bool CrackedPoint<Space, Point>::bandHasFailed(const Band& b) const {
  const Point& p = self();
  const JumpMap N = Space::jumpMap(b.crackNormal);
  const Jump traction =
      b.integrity * (N.transpose() * (p.stiffness() * (b.onsetStrain + N * b.jump / p.bandWidth())));  // Eq. (11)
  return traction.norm() < cracked::Limits::kFailedTraction * p.tensileStrength();
}

// Both > 0 where the state with this K is stable under the caller's control (scaled,
// continuous): the smallest real eigenvalue of K scaled by its intact secant value
// mu (f / (1 - f) + 1) / h, and (mixed control: the Jacobian of (jump, stress-controlled
// strains) has det K det D_ss, a Schur complement) that of the stress-controlled block of D.
template <class Space, class Point>
Eigen::Vector2d CrackedPoint<Space, Point>::stabilityMargins(const Band& b, const JumpJacobian& jacobian, unsigned stressControlled) const {
  const Point& p = self();
  const double kMargin = smallestRealEigenvalue(jacobian) * p.bandWidth() /
                         (p.shearModulus() * (b.volumeFraction / (1.0 - b.volumeFraction) + 1.0));
  if (stressControlled == 0 || !(kMargin > 0.0)) return {kMargin, 1.0};
  return {kMargin, p.stressControlledMargin(consistentTangent(b, jacobian), stressControlled)};
}

// Snap-back on the path (docs/model.md): along the straight jump segment from the converged state
// b to `jump`, the band on its loading surface (elastic inside it, loading beyond it), the first
// fraction t in [0, 1] where the state stops being stable; nullopt if it stays stable. K of
// Eq. (9) and D of Eq. (10) depend on the jump only.
template <class Space, class Point>
std::optional<double> CrackedPoint<Space, Point>::firstUnstableOnPath(const Band& b, const LoadingSurface& surface, const Jump& jump,
                                                                 unsigned stressControlled) const {
  const Point& p = self();
  const Jump delta = jump - b.jump;
  const auto margins = [&](double t) {
    return stabilityMargins(b, loadingJacobian(b, surface, Jump(b.jump + t * delta)), stressControlled);
  };
  const double floor = -cracked::Limits::kMarginFloor;
  // The first zero of margin i between a stable fraction and an unstable one (bisection).
  const auto crossing = [&](int i, double stable, double unstable) {
    for (int it = 0; it < 50 && unstable - stable > 1e-14; ++it) {
      const double mid = 0.5 * (stable + unstable);
      (margins(mid)[i] > floor ? stable : unstable) = mid;
    }
    return unstable;
  };
  // Samples: every kJumpCheck h (at least kJumpSamples, at most kMaxPathSamples), and
  // geometrically closer towards the start, where the softening branch turns fastest.
  const double length = delta.norm();
  // (Clamped as a double before the cast: a huge jump's count does not fit an int; NaN gives the fewest.)
  const int uniform = static_cast<int>(std::fmin(std::fmax(std::ceil(length / (cracked::Limits::kJumpCheck * p.bandWidth())),
                                                           double(cracked::Limits::kJumpSamples)),
                                                 double(cracked::Limits::kMaxPathSamples)));
  std::vector<double> ts;
  ts.reserve(uniform + 400);
  for (int k = 0; k <= uniform; ++k) ts.push_back(double(k) / uniform);
  for (double t = cracked::Limits::kFirstGeometricSample; t < 1.0 / uniform; t *= cracked::Limits::kGeometricRatio) ts.push_back(t);
  std::sort(ts.begin(), ts.end());
  const int count = static_cast<int>(ts.size());
  std::vector<Eigen::Vector2d> sampled(count);
  for (int k = 0; k < count; ++k) {
    sampled[k] = margins(ts[k]);
    for (int i = 0; i < 2; ++i)
      if (!(sampled[k][i] > floor)) return k == 0 ? 0.0 : crossing(i, ts[k - 1], ts[k]);
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
    std::sort(minima.begin(), minima.end(), [&](int a, int c) { return sampled[a][i] < sampled[c][i]; });
    if (minima.size() > cracked::Limits::kRefinedMinima) minima.resize(cracked::Limits::kRefinedMinima);
    const auto margin = [&](double t) { return margins(t)[i]; };
    for (int k : minima) {
      const double left = ts[std::max(0, k - 1)];
      double lo = left, hi = ts[std::min(count - 1, k + 1)];
      double t1 = hi - g * (hi - lo), t2 = lo + g * (hi - lo), m1 = margin(t1), m2 = margin(t2);
      for (int it = 0; it < 50 && hi - lo > 1e-12 * (ts[std::min(count - 1, k + 1)] - left); ++it) {
        if (!(m1 > floor) || !(m2 > floor)) {
          const double t = crossing(i, left, !(m1 > floor) ? t1 : t2);
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

// The cracked update proper: elastic predictor, then damage corrector on the envelope. On
// failure the state is left unchanged.
template <class Space, class Point>
typename CrackedPoint<Space, Point>::Result CrackedPoint<Space, Point>::predictCorrect(Band& b, Strain& strain, const Strain& increment, bool tangent,
                                                                      unsigned stressControlled) const {
  const Point& p = self();
  const BandDamageLaw& law = p.bandLaw();
  const Strain eps = strain + increment;
  Result res;
  const Strain aEps = p.stiffness() * eps;
  const double f = b.volumeFraction;
  const double tol = crackedTolerance(aEps, f);

  // 1. Elastic predictor: with the band's damage frozen, Eq. (6) is linear in [u] and the secant
  //    K of Eq. (9) (a_L = x0 a, always positive definite) solves it in one step. If the band
  //    stays inside its loading surface, that is the answer (unloading or neutral loading):
  //    most cracked updates of a structure end here, without the damage law or its tangent.
  const JumpMap N = Space::jumpMap(b.crackNormal);
  const double x0 = b.integrity;
  Jump jump = b.jump;
  Strain aBand = p.stiffness() * (b.onsetStrain + N * jump / p.bandWidth());                    // a eps_L, Eq. (3)
  const auto stressOf = [&](const Strain& aL) -> Strain { return (aEps - f * aL) / (1.0 - f); };  // Eqs. (2), (4)
  Jump residual = N.transpose() * (stressOf(aBand) - x0 * aBand);                                 // Eqs. (6), (11)
  for (int it = 0; it < 3 && residual.norm() > tol; ++it) {  // 1 step + round-off
    jump += p.secantSolve(b, x0, residual);
    aBand = p.stiffness() * (b.onsetStrain + N * jump / p.bandWidth());
    residual = N.transpose() * (stressOf(aBand) - x0 * aBand);
    ++res.iterations;
  }
  // The loading surface F(x0) >= F(1): a band whose Y is below onset (a closed or barely open
  // crack) is unloading without evaluating F (a pow).
  const double y = p.bandDrivingForce(aBand);
  const bool belowOnset = y <= law.onsetDrivingForce();
  const BandDamageLaw::LoadingSurface surface =
      belowOnset ? BandDamageLaw::LoadingSurface{x0, law.onsetDrivingForce()} : law.loadingSurface(x0);
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
  Equilibrium eq = equilibrium(b, envelope, eps, jump, true);
  double rn = eq.residual.norm();
  bool sawUnstableBranch = false;
  int it = 0;
  for (; rn > tol && it < cracked::Limits::kMaxIterations; ++it) {
    const Jump step = eq.jacobian.partialPivLu().solve(eq.residual);
    if (!step.allFinite()) break;
    double alpha = 1.0;
    Equilibrium trial;
    for (int ls = 0; ls < 40; ++ls, alpha *= 0.5) {
      trial = equilibrium(b, envelope, eps, Jump(jump + alpha * step), true);
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
    if (eq.band.drivingForce < surface.threshold * (1.0 - cracked::Limits::kNeutralLoading)) {
      res.status = UpdateStatus::SnapBack;
      return res;
    }
    eq = equilibrium(b, surface, eps, jump, false);  // neutral: the secant K, damage unchanged
  } else if (stressControlled == 0 ? !positiveDefinite(eq.jacobian)
                                    : !(stabilityMargins(b, eq.jacobian, stressControlled).minCoeff() > -cracked::Limits::kMarginFloor)) {
    res.status = UpdateStatus::SnapBack;  // a root on the unstable branch
    return res;
  }
  // The root is stable; the path to it must be too (docs/model.md, "Snap-back on the path"): a
  // loading increment whose jump is longer than kJumpCheck h may have passed a limit point.
  if ((jump - b.jump).norm() > cracked::Limits::kJumpCheck * p.bandWidth() && !bandHasFailed(b) &&
      firstUnstableOnPath(b, surface, jump, stressControlled)) {
    res.status = UpdateStatus::SnapBack;
    return res;
  }
  // Commit the converged equilibrium: the tangent of Eq. (10) and f int Y dD (on the loading
  // branch F(x_new) = Y).
  res.residual = eq.residual.norm();
  res.stress = eq.stress;
  if (!(res.residual <= tol)) {
    res.status = UpdateStatus::NotConverged;
    return res;
  }
  res.status = UpdateStatus::Converged;
  if (tangent) res.tangent = consistentTangent(b, eq.jacobian);
  res.dissipation = f * law.dissipation(b.integrity, eq.band.integrity, surface.threshold, eq.band.drivingForce);
  b.jump = jump;
  b.integrity = eq.band.integrity;
  strain = eps;
  return res;
}

template <class Space, class Point>
typename CrackedPoint<Space, Point>::Result CrackedPoint<Space, Point>::releaseSnapBack(Band& b, Strain& strain, const Strain& increment, bool tangent) const {
  const Point& p = self();
  const BandDamageLaw& law = p.bandLaw();
  const Strain eps = strain + increment;
  const double f = b.volumeFraction;
  // With the damage frozen at x, Eq. (6) is linear in [u] (secant K of Eq. (9)): [u](x) in one
  // solve. The band is in equilibrium with consistent damage where g(x) = Y([u](x)) / F(x) - 1 = 0.
  // g > 0 at x0 (the band must load); g -> -inf as x -> 0 (material/release_scan.hpp).
  struct Probe {
    double g;
    Band band;
  };
  const auto probe = [&](double x) {
    Probe pr{0.0, b};
    pr.band.integrity = x;
    const BandDamageLaw::LoadingSurface frozen{x, std::numeric_limits<double>::infinity()};
    const Equilibrium eq = equilibrium(pr.band, frozen, eps, b.jump, false);
    pr.band.jump = b.jump + p.secantStep(b, x, eq.residual);
    const Equilibrium moved = equilibrium(pr.band, frozen, eps, pr.band.jump, false);
    pr.g = moved.band.drivingForce / damageFunction(law.law(), x) - 1.0;
    return pr;
  };
  Result res;
  res.status = UpdateStatus::SnapBack;
  // Polish each root with the regular update at zero increment: it confirms continuity, loading
  // consistency and stability (K of Eq. (9) positive), or reports this root unstable.
  releaseScan(probe, b.integrity, res.iterations, [&](const Probe& root) {
    Band trial = root.band;
    Strain s = eps;
    const Result r = predictCorrect(trial, s, Strain::Zero().eval(), tangent, 0);
    const bool isStable =
        r.converged() && positiveDefinite(equilibrium(trial, law.envelope(trial.integrity), eps, trial.jump, true).jacobian);
    if (!isStable) return false;
    res = r;
    res.iterations += r.iterations;
    res.released = true;
    res.dissipation = f * law.dissipation(b.integrity, trial.integrity);  // f int Y dD over the release
    b = trial;
    strain = eps;
    return true;
  });
  return res;
}

// The cracked update under the snap-back policy: predictor-corrector, then (release) the band
// fails onto its stable branch where the loading branch turned back. Newton on the envelope can
// also stall without meeting an unstable state it could name: where the nearest consistent state
// lies a damage jump away (a nearly intact band, Y with the kink of Eq. (12) as a principal stress
// crosses zero). The release's scan in x finds that state; if it finds none, the stall is
// reported as it was.
template <class Space, class Point>
typename CrackedPoint<Space, Point>::Result CrackedPoint<Space, Point>::updateCracked(Band& b, Strain& strain, const Strain& increment, UpdateOptions options) const {
  const Result r = predictCorrect(b, strain, increment, options.tangent, options.stressControlled);
  if (r.converged() || options.snapBack != SnapBackPolicy::Release) return r;
  if (r.status == UpdateStatus::SnapBack) return releaseSnapBack(b, strain, increment, options.tangent);
  const Result released = releaseSnapBack(b, strain, increment, options.tangent);
  return released.converged() ? released : r;
}

}  // namespace ecm
