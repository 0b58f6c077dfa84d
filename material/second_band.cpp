// The second band of an enriched point (docs/model.md, "A second band"). A cracked point opens
// a band across its first band's tangent t1 once the bulk stress along t1 meets the onset
// criterion. Then eps = f1 eps_L1 + f2 eps_L2 + (1 - f1 - f2) eps_b, and traction continuity,
// Eq. (6), holds on both bands. The one-band update (two_phase_point.cpp) is untouched: a point
// pays for this file only once it has two bands, or while the option looks for the trigger.
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "material/driving_force.hpp"
#include "material/free_sliding.hpp"
#include "material/two_phase_point.hpp"
#include "material/release_scan.hpp"

namespace ecm {

namespace {

using Surface = BandDamageLaw::LoadingSurface;
constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr int kActiveSetPasses = 6;

// The smallest real part of K's eigenvalues: > 0 where the two-band branch is locally unique
// and stable (Eq. (9) extended).
double smallestRealPart(const Mat4& k) { return Eigen::EigenSolver<Mat4>(k, false).eigenvalues().real().minCoeff(); }

// The band's damage frozen at x: the law stays elastic with a_L = x a (a secant evaluation).
Surface frozenAt(double x) { return {x, kInfinity}; }

}  // namespace

double TwoPhasePoint::tangentialStress(const BandState& first, const Voigt& stress) const {
  return normalProjector(first.slidingDirection()).dot(stress);
}

BandState TwoPhasePoint::openSecondBand(const BandState& first, const Voigt& strain, const EffectiveSize& size) const {
  BandState b;
  b.crackNormal = canonicalNormal(first.slidingDirection() + Vec2::Zero());  // (+ 0: no -0 component)
  const double f1 = first.volumeFraction;
  const Voigt firstBandStrain = first.onsetStrain + jumpToStrain(first.crackNormal) * first.jump / bandWidth_;  // Eq. (3)
  b.onsetStrain = (strain - f1 * firstBandStrain) / (1.0 - f1);  // eps_L2 = eps_b of Eq. (2): sigma continuous
  b.volumeFraction = bandWidth_ / size(b.crackNormal);  // Eq. (1) for the second band's normal
  return b;
}

TwoBandEquilibrium TwoPhasePoint::equilibrium(const BandState& first, const BandState& second,
                                             const Surface (&surfaces)[2], const Voigt& strain, const Vec4& jumps,
                                             bool loadingTangent) const {
  const JumpMap N[2] = {jumpToStrain(first.crackNormal), jumpToStrain(second.crackNormal)};
  const double f[2] = {first.volumeFraction, second.volumeFraction};
  const double bulk = 1.0 - f[0] - f[1];
  const Tangent& a = stiffness();
  TwoBandEquilibrium eq;
  eq.bandStrain[0] = first.onsetStrain + N[0] * jumps.head<2>() / bandWidth_;   // Eq. (3)
  eq.bandStrain[1] = second.onsetStrain + N[1] * jumps.tail<2>() / bandWidth_;
  eq.band[0] = law_.evaluate(surfaces[0], eq.bandStrain[0], loadingTangent);   // Eqs. (5), (11)-(13)
  eq.band[1] = law_.evaluate(surfaces[1], eq.bandStrain[1], loadingTangent);
  eq.stress = a * (strain - f[0] * eq.bandStrain[0] - f[1] * eq.bandStrain[1]) / bulk;  // Eqs. (2), (4)
  for (int i = 0; i < 2; ++i) {
    eq.residual.segment<2>(2 * i) = N[i].transpose() * (eq.stress - eq.band[i].stress);  // Eq. (6)
    for (int j = 0; j < 2; ++j) {
      Mat2 block = N[i].transpose() * (f[j] / bulk * a) * N[j];  // Eq. (9): the bulk couples the bands
      if (i == j) block += N[i].transpose() * eq.band[i].tangent * N[i];
      eq.jacobian.block<2, 2>(2 * i, 2 * j) = block / bandWidth_;
    }
  }
  return eq;
}

Tangent TwoPhasePoint::consistentTangent(const BandState& first, const BandState& second, const Mat4& jacobian) const {
  const JumpMap N[2] = {jumpToStrain(first.crackNormal), jumpToStrain(second.crackNormal)};
  const double f[2] = {first.volumeFraction, second.volumeFraction};
  const double bulk = 1.0 - f[0] - f[1];
  const Tangent& a = stiffness();
  Eigen::Matrix<double, 4, 3> g;
  for (int i = 0; i < 2; ++i) g.block<2, 3>(2 * i, 0) = N[i].transpose() * a / bulk;  // d residual / d eps, Eq. (8)
  const Eigen::Matrix<double, 4, 3> dJumps = solveJumps<3>(jacobian, g, bandHasFailed(first) && bandHasFailed(second));
  Tangent s = Tangent::Identity();
  for (int j = 0; j < 2; ++j) s -= f[j] / bandWidth_ * N[j] * dJumps.block<2, 3>(2 * j, 0);
  return a / bulk * s;  // Eq. (10)
}

double TwoPhasePoint::storedEnergy(const BandState& first, const BandState* second, const Voigt& strain) const {
  const Tangent& a = stiffness();
  const BandState* bands[2] = {&first, second};
  double bandEnergy = 0.0, fractions = 0.0;
  Voigt bulkStrain = strain;
  for (const BandState* b : bands) {
    if (!b) continue;
    const Voigt bandStrain = b->onsetStrain + jumpToStrain(b->crackNormal) * b->jump / bandWidth_;  // Eq. (3)
    bandEnergy += b->volumeFraction * 0.5 * b->integrity * bandStrain.dot(a * bandStrain);       // Eq. (11)
    bulkStrain -= b->volumeFraction * bandStrain;
    fractions += b->volumeFraction;
  }
  bulkStrain /= 1.0 - fractions;  // Eq. (2)
  return (1.0 - fractions) * 0.5 * bulkStrain.dot(a * bulkStrain) + bandEnergy;
}

Voigt TwoPhasePoint::stress(const BandState& first, const BandState& second, const Voigt& strain) const {
  const Surface frozen[2] = {frozenAt(first.integrity), frozenAt(second.integrity)};
  Vec4 jumps;
  jumps << first.jump, second.jump;
  return equilibrium(first, second, frozen, strain, jumps, false).stress;
}

double TwoPhasePoint::twoBandTolerance(const BandState& first, const BandState& second, const Voigt& eps) const {
  const double f = first.volumeFraction + second.volumeFraction;
  return kRelativeTolerance * tensileStrength() + kRoundOff * (stiffness() * eps).norm() * std::max(1.0, f / (1.0 - f));
}

TwoPhasePoint::TwoBandSolve TwoPhasePoint::solveTwoBands(const BandState& first, const BandState& second,
                                                       const Surface (&surfaces)[2], const Voigt& eps, Vec4 jumps,
                                                       double tol) const {
  // Newton with line search on Eq. (6) for both bands; frozen bands make it linear in their jumps.
  TwoBandSolve s;
  s.eq = equilibrium(first, second, surfaces, eps, jumps, true);
  const FreeSliding free(s.eq.jacobian, bandHasFailed(first) && bandHasFailed(second));
  // Where the sliding is free and the bands have opened far, the bulk strain (eps less f_i eps_Li,
  // over 1 - f1 - f2) carries the round-off of f_i eps_Li, not only of eps: a Newton that stalls
  // above `tol` is accepted within that floor.
  double floor = tol;
  if (free.active) {
    const BandState* bands[2] = {&first, &second};
    double bandStress = 0.0;
    for (int i = 0; i < 2; ++i) {
      const Voigt bandStrain = bands[i]->onsetStrain + jumpToStrain(bands[i]->crackNormal) * jumps.segment<2>(2 * i) / bandWidth_;  // Eq. (3)
      bandStress += bands[i]->volumeFraction * (stiffness() * bandStrain).norm();
    }
    floor += kRoundOff * bandStress / (1.0 - first.volumeFraction - second.volumeFraction);
  }
  const auto measure = [&](const TwoBandEquilibrium& e) { return free.active ? free.rangeNorm(e.residual) : e.residual.norm(); };
  double rn = measure(s.eq);
  for (; rn > tol && s.iterations < kMaxIterations; ++s.iterations) {
    const Vec4 step = free.active ? Vec4(free.svd.solve(s.eq.residual)) : Vec4(s.eq.jacobian.partialPivLu().solve(s.eq.residual));
    if (!step.allFinite()) break;
    double alpha = 1.0;
    TwoBandEquilibrium trial;
    double trialNorm = rn;
    for (int ls = 0; ls < 40; ++ls, alpha *= 0.5) {
      trial = equilibrium(first, second, surfaces, eps, jumps + alpha * step, true);
      trialNorm = measure(trial);
      if (trialNorm < (1.0 - 1e-4 * alpha) * rn) break;
    }
    if (free.active && alpha < 1e-6) break;  // stalled at its round-off floor
    jumps += alpha * step;
    s.eq = trial;
    rn = trialNorm;
    // det K <= 0: an odd number of eigenvalues on the unstable side (the full test, on the
    // eigenvalues, is made at the root; this flag only names a failed Newton a snap-back).
    if ((s.eq.band[0].loading || s.eq.band[1].loading) && !(s.eq.jacobian.determinant() > 0.0))
      s.sawUnstableBranch = true;
  }
  s.jumps = jumps;
  s.converged = rn <= tol || (free.active && rn <= floor);
  return s;
}

double TwoPhasePoint::twoBandMargin(const BandState& first, const BandState& second, const Mat4& jacobian,
                                   unsigned stressControlled) const {
  // K scaled by its intact secant value mu / ((1 - f1 - f2) h); under mixed control also the
  // stress-controlled block of D (Eq. (10)), scaled by E: both > 0 where the state is stable.
  const double bulk = 1.0 - first.volumeFraction - second.volumeFraction;
  const double kMargin = smallestRealPart(jacobian) * bandWidth_ * bulk / shearModulus_;
  if (stressControlled == 0 || !(kMargin > 0.0)) return kMargin;
  return std::min(kMargin, stressControlledMargin(consistentTangent(first, second, jacobian), stressControlled));
}

UpdateResult TwoPhasePoint::updateTwoBands(BandState& first, BandState& second, Voigt& strain, const Voigt& increment,
                                          UpdateOptions options) const {
  const Voigt eps = strain + increment;
  const double tol = twoBandTolerance(first, second, eps);
  BandState* bands[2] = {&first, &second};
  UpdateResult res;
  const auto fail = [&](UpdateStatus status, double residual) {
    res.status = status;
    res.residual = residual;
    return options.snapBack == SnapBackPolicy::Release ? releaseTwoBands(first, second, strain, increment, options.tangent)
                                                       : res;
  };

  // 1. Elastic predictor: both damages frozen, Eq. (6) linear in the jumps.
  const Surface frozen[2] = {frozenAt(first.integrity), frozenAt(second.integrity)};
  Vec4 start;
  start << first.jump, second.jump;
  const TwoBandSolve predictor = solveTwoBands(first, second, frozen, eps, start, tol);
  res.iterations = predictor.iterations;
  if (!predictor.converged) return fail(UpdateStatus::NotConverged, predictor.eq.residual.norm());
  const Surface surface[2] = {law_.loadingSurface(first.integrity), law_.loadingSurface(second.integrity)};
  bool loading[2];
  for (int i = 0; i < 2; ++i) loading[i] = predictor.eq.band[i].drivingForce > surface[i].threshold;

  // 2. Damage corrector: the loading bands on their envelopes, the others frozen; a band whose
  //    root heals unloads, a frozen band whose Y passes its surface loads, until the set holds.
  TwoBandSolve sol = predictor;
  bool settled = !loading[0] && !loading[1];
  for (int pass = 0; pass < kActiveSetPasses && !settled; ++pass) {
    const Surface s[2] = {loading[0] ? BandDamageLaw::envelope(surface[0]) : frozen[0],
                          loading[1] ? BandDamageLaw::envelope(surface[1]) : frozen[1]};
    sol = solveTwoBands(first, second, s, eps, predictor.jumps, tol);
    res.iterations += sol.iterations;
    if (!sol.converged)
      return fail(sol.sawUnstableBranch ? UpdateStatus::SnapBack : UpdateStatus::NotConverged, sol.eq.residual.norm());
    settled = true;
    for (int i = 0; i < 2; ++i) {
      const BandResponse& r = sol.eq.band[i];
      if (loading[i] && !(r.integrity < bands[i]->integrity)) {
        loading[i] = false, settled = false;  // the other band's loading unloads it, or neutral: frozen at x0
      } else if (!loading[i] && r.drivingForce > surface[i].threshold * (1.0 + kNeutralLoading)) {
        loading[i] = true, settled = false;
      }
    }
  }
  // A set that never holds (a band loads frozen and heals loading) has no loading branch
  // under strain control: for one band that is the snap-back of two_phase_point.cpp.
  if (!settled) return fail(UpdateStatus::SnapBack, sol.eq.residual.norm());
  if (loading[0] || loading[1]) {
    // Stable under the caller's control at the root, and along the path to it (docs/model.md,
    // "Snap-back on the path": sampled every kJumpCheck h, 8 to 256 samples, and geometrically
    // towards the start), each band on its loading surface of the increment's start.
    if (!(twoBandMargin(first, second, sol.eq.jacobian, options.stressControlled) > -kMarginFloor))
      return fail(UpdateStatus::SnapBack, sol.eq.residual.norm());
    const Vec4 delta = sol.jumps - start;
    if (delta.norm() > kJumpCheck * bandWidth_ && !(bandHasFailed(first) && bandHasFailed(second))) {
      const Surface path[2] = {loading[0] ? surface[0] : frozen[0], loading[1] ? surface[1] : frozen[1]};
      // (Clamped as a double before the cast: a huge jump's count does not fit an int.)
      const int uniform = static_cast<int>(std::fmin(
          std::fmax(std::ceil(delta.norm() / (kJumpCheck * bandWidth_)), double(kJumpSamples)), double(kMaxPathSamples)));
      std::vector<double> ts;
      for (int k = 1; k < uniform; ++k) ts.push_back(double(k) / uniform);
      for (double t = kFirstGeometricSample; t < 1.0 / uniform; t *= kGeometricRatio) ts.push_back(t);
      for (const double t : ts) {
        const TwoBandEquilibrium at = equilibrium(first, second, path, eps, start + t * delta, true);
        if (!(twoBandMargin(first, second, at.jacobian, options.stressControlled) > -kMarginFloor))
          return fail(UpdateStatus::SnapBack, sol.eq.residual.norm());
      }
    }
  }

  // 3. Commit: f_i int Y_i dD_i on each loading band (on the branch F(x_new) = Y).
  res.status = UpdateStatus::Converged;
  res.residual = sol.eq.residual.norm();
  res.stress = sol.eq.stress;
  if (options.tangent) res.tangent = consistentTangent(first, second, sol.eq.jacobian);
  for (int i = 0; i < 2; ++i) {
    BandState& b = *bands[i];
    if (loading[i]) {
      res.dissipation += b.volumeFraction * law_.dissipation(b.integrity, sol.eq.band[i].integrity, surface[i].threshold,
                                                             sol.eq.band[i].drivingForce);
      b.integrity = sol.eq.band[i].integrity;
    }
    b.jump = sol.jumps.segment<2>(2 * i);
  }
  strain = eps;
  return res;
}

UpdateResult TwoPhasePoint::releaseTwoBands(BandState& first, BandState& second, Voigt& strain, const Voigt& increment,
                                           bool tangent) const {
  // As releaseSnapBack for one band: at the end strain, the damage of the band that loads most
  // (the larger Y / F(x0) at the predictor) is scanned down geometrically; the other band follows
  // its envelope if it loads too, else stays frozen. g(x) = Y(x) / F(x) - 1 changes sign at a
  // consistent state; the first one the regular update confirms stable is taken.
  const Voigt eps = strain + increment;
  const double tol = twoBandTolerance(first, second, eps);
  const BandState* bands[2] = {&first, &second};
  const Surface surface[2] = {law_.loadingSurface(first.integrity), law_.loadingSurface(second.integrity)};
  Vec4 jumps;
  jumps << first.jump, second.jump;
  const Surface frozen[2] = {frozenAt(first.integrity), frozenAt(second.integrity)};
  const TwoBandSolve predictor = solveTwoBands(first, second, frozen, eps, jumps, tol);
  UpdateResult res;
  res.status = UpdateStatus::SnapBack;
  if (!predictor.converged) return res;
  double ratio[2];
  for (int i = 0; i < 2; ++i) ratio[i] = predictor.eq.band[i].drivingForce / surface[i].threshold;
  // The scan of one band's damage; false if it finds no stable consistent state.
  const auto scan = [&](const int scanned, const bool otherLoads) {
    const int other = 1 - scanned;
    const Surface otherSurface = otherLoads ? BandDamageLaw::envelope(surface[other]) : frozen[other];
    struct Probe {
      double x = 1.0, g = 0.0;
      TwoBandSolve solve;
    };
    Vec4 guess = predictor.jumps;
    const auto probe = [&](double x) {
      Probe p;
      p.x = x;
      Surface s[2];
      s[scanned] = frozenAt(x);
      s[other] = otherSurface;
      p.solve = solveTwoBands(first, second, s, eps, guess, tol);
      p.g = p.solve.converged ? p.solve.eq.band[scanned].drivingForce / damageFunction(law_.law(), x) - 1.0
                              : std::numeric_limits<double>::quiet_NaN();
      if (p.solve.converged) guess = p.solve.jumps;
      return p;
    };
    // hi: the last probe that converged (one that did not is stepped over, not bracketed).
    Probe hi = probe(bands[scanned]->integrity);
    double x = hi.x;
    for (int k = 0; k < kMaxReleaseSteps && x > 1e-300; ++k) {
      x *= kReleaseScanRatio;
      Probe lo = probe(x);
      ++res.iterations;
      if (!lo.solve.converged) continue;
      if (!(lo.g <= 0.0) || !(hi.g > 0.0)) {
        hi = lo;
        continue;
      }
      double la = std::log(lo.x), lb = std::log(hi.x), ga = lo.g, gb = hi.g;
      Probe below = lo, above = hi, root = lo;  // the bracket's ends (g <= 0, g > 0)
      int side = 0;
      for (int it = 0; it < 100 && lb - la > 1e-15 * std::abs(lb) + 1e-300; ++it) {  // Illinois in log x
        const double lc = (la * gb - lb * ga) / (gb - ga);
        // Newton from the nearer end of the bracket (the last probe may lie on the other side);
        // where it fails, bisect.
        guess = (lc - la < lb - lc ? below : above).solve.jumps;
        root = probe(std::exp(lc));
        if (!root.solve.converged) {
          guess = above.solve.jumps;
          root = probe(std::exp(0.5 * (la + lb)));
          if (!root.solve.converged) break;
        }
        ++res.iterations;
        const double l = std::log(root.x);
        if (!(std::abs(root.g) > 1e-14)) break;
        if (root.g < 0.0) {
          la = l, ga = root.g, below = root;
          if (side == -1) gb *= 0.5;
          side = -1;
        } else {
          lb = l, gb = root.g, above = root;
          if (side == +1) ga *= 0.5;
          side = +1;
        }
      }
      if (!root.solve.converged) {
        hi = lo;
        continue;
      }
      // Polish with the regular update at zero increment: continuity, consistency, stability.
      BandState trial[2] = {first, second};
      for (int i = 0; i < 2; ++i) trial[i].jump = root.solve.jumps.segment<2>(2 * i);
      trial[scanned].integrity = root.x;
      if (otherSurface.envelope) trial[other].integrity = std::min(trial[other].integrity, root.solve.eq.band[other].integrity);
      Voigt s = eps;
      UpdateOptions polish(SnapBackPolicy::Stop, tangent);
      const UpdateResult r = updateTwoBands(trial[0], trial[1], s, Voigt::Zero(), polish);
      if (r.converged()) {
        res = r;
        res.iterations += r.iterations;
        res.released = true;
        res.dissipation = first.volumeFraction * law_.dissipation(first.integrity, trial[0].integrity) +
                          second.volumeFraction * law_.dissipation(second.integrity, trial[1].integrity);
        first = trial[0];
        second = trial[1];
        strain = eps;
        return true;
      }
      hi = lo;
    }
    return false;
  };
  // The band that loads most, the other on its envelope if it loads too. If that finds no stable
  // state and the other loads too: the same band with the other frozen, then the other band.
  // Where a second band opens next to a nearly failed first band, both load at the predictor and
  // the stable state has the first band unloading (docs/model.md, "A second band").
  const int preferred = ratio[1] > ratio[0] ? 1 : 0, other = 1 - preferred;
  const bool otherLoads = ratio[other] > 1.0;
  struct Try {
    int scanned;
    bool otherLoads;
  };
  std::vector<Try> tries{{preferred, otherLoads}};
  if (otherLoads) tries.insert(tries.end(), {{preferred, false}, {other, ratio[preferred] > 1.0}});
  int iterations = 0;
  for (const Try& t : tries) {
    res.iterations = 0;
    if (scan(t.scanned, t.otherLoads)) {
      res.iterations += iterations;
      return res;
    }
    iterations += res.iterations;
  }
  res = UpdateResult{};
  res.status = UpdateStatus::SnapBack;
  res.iterations = iterations;
  return res;
}

UpdateResult TwoPhasePoint::updateCracked(BandState& first, BandState* second, Voigt& strain, const Voigt& increment,
                                         const EffectiveSize& size, std::optional<BandState>& secondOnset,
                                         UpdateOptions options) const {
  if (second) return updateTwoBands(first, *second, strain, increment, options);
  if (!opensSecondBand()) return updateCracked(first, strain, increment, options);
  const BandState startBand = first;
  const Voigt startStrain = strain;
  UpdateResult r = updateCracked(first, strain, increment, options);
  if (!r.converged() || !(tangentialStress(first, r.stress) >= secondOnsetStress_)) return r;

  // The trigger is met inside the increment: find its exact onset alpha, sigma_tt(alpha) = the
  // onset stress, along the one-band response from the increment's start (Illinois regula falsi).
  struct At {
    BandState band;
    Voigt strain;
    UpdateResult r;
    double g;
  };
  const auto at = [&](double alpha) {
    At s{startBand, startStrain, {}, 0.0};
    s.r = updateCracked(s.band, s.strain, alpha * increment, options);
    s.g = s.r.converged() ? tangentialStress(s.band, s.r.stress) - secondOnsetStress_ : std::numeric_limits<double>::quiet_NaN();
    return s;
  };
  At hi{first, strain, r, tangentialStress(first, r.stress) - secondOnsetStress_};
  double alpha = 1.0;
  At lo = at(0.0);
  if (!(lo.g < 0.0)) {
    hi = lo, alpha = 0.0;  // open at the start of the increment
  } else {
    double a = 0.0, b = 1.0, ga = lo.g, gb = hi.g;
    int side = 0;
    for (int it = 0; it < 100 && b - a > 1e-15; ++it) {
      const double c = (a * gb - b * ga) / (gb - ga);
      At mid = at(c);
      if (!(mid.g == mid.g)) break;  // a failed one-band update: keep the bracket's end
      if (mid.g >= 0.0) {
        hi = mid, b = c, gb = mid.g;
        if (side == +1) ga *= 0.5;
        side = +1;
        if (mid.g <= 1e-12 * secondOnsetStress_) break;
      } else {
        a = c, ga = mid.g;
        if (side == -1) gb *= 0.5;
        side = -1;
      }
    }
    alpha = b;
  }
  BandState opened = openSecondBand(hi.band, hi.strain, size);
  // Both bands need a bulk: 1 - f1 - f2 >= 1e-6 / (1 + 1e-6), i.e. H >= 2 h (1 + 1e-6) for equal sizes.
  if (!(1.0 - hi.band.volumeFraction - opened.volumeFraction >= kMinimumSizeMargin / (1.0 + kMinimumSizeMargin))) {
    first = startBand;
    strain = startStrain;
    UpdateResult refused;
    refused.status = UpdateStatus::SizeTooSmall;
    refused.refusedSize = bandWidth_ / std::max(hi.band.volumeFraction, opened.volumeFraction);  // the smaller H
    return refused;
  }
  BandState band = hi.band;
  Voigt s = hi.strain;
  // Does the band open continuously? Where the first band still carries traction, the second
  // band's Y may start above F(0); its damage then catches up at the trigger's strain, a jump
  // with no continuous branch: a snap-back. Released, it books the stored energy the jump
  // releases, psi before minus psi after at the same strain (docs/model.md, "A second band").
  double jumpEnergy = 0.0;
  bool jumped = false;
  {
    BandState landedFirst = band, landedSecond = opened;
    Voigt at = s;
    UpdateOptions land = options;
    land.snapBack = SnapBackPolicy::Stop;
    const UpdateResult landed = updateTwoBands(landedFirst, landedSecond, at, Voigt::Zero(), land);
    if (landed.converged() && (landed.stress - hi.r.stress).norm() > twoBandTolerance(landedFirst, landedSecond, at)) {
      if (options.snapBack != SnapBackPolicy::Release) {
        first = startBand;
        strain = startStrain;
        UpdateResult snap;
        snap.status = UpdateStatus::SnapBack;
        snap.iterations = hi.r.iterations + landed.iterations;
        return snap;
      }
      jumpEnergy = std::max(0.0, storedEnergy(band, &opened, s) - storedEnergy(landedFirst, &landedSecond, at));
      band = landedFirst;
      opened = landedSecond;
      jumped = true;
    }
  }
  UpdateResult rest = updateTwoBands(band, opened, s, (1.0 - alpha) * increment, options);
  if (!rest.converged()) {
    first = startBand;
    strain = startStrain;
    return rest;
  }
  first = band;
  strain = s;
  secondOnset = opened;
  rest.dissipation += hi.r.dissipation + jumpEnergy;
  rest.iterations += hi.r.iterations;
  rest.released = rest.released || hi.r.released || jumped;
  return rest;
}

UpdateResult TwoPhasePoint::updateIntact(Voigt& strain, const Voigt& increment, const EffectiveSize& size,
                                        std::optional<BandState>& onset, std::optional<BandState>& secondOnset,
                                        UpdateOptions options) const {
  const Voigt end = strain + increment;
  const Voigt s = stiffness() * end;
  if (surelyIntact(s)) {
    strain = end;
    return {s, stiffness()};
  }
  return updateIntactSlow(strain, increment, size, onset, options, opensSecondBand() ? &secondOnset : nullptr);
}

}  // namespace ecm
