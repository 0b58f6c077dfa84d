#include "material/two_phase_point_3d.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <Eigen/Eigenvalues>

#include "material/band_onset.hpp"
#include "material/parameter_check.hpp"
#include "material/release_scan.hpp"

namespace ecm {

namespace {

// All eigenvalues of a 3x3 with positive real part (Routh-Hurwitz on det(s I + K)): the
// traction-continuity system of Eq. (9) has a locally unique, stable solution branch.
bool positiveDefinite3(const Mat3& k) {
  const double t = k.trace();
  const double m = k(0, 0) * k(1, 1) - k(0, 1) * k(1, 0) + k(1, 1) * k(2, 2) - k(1, 2) * k(2, 1) + k(0, 0) * k(2, 2) -
                   k(0, 2) * k(2, 0);
  const double d = k.determinant();
  return t > 0.0 && d > 0.0 && t * m > d;
}

template <class Matrix>
double smallestRealEigenvalue(const Matrix& k) {
  return Eigen::EigenSolver<Matrix>(k, false).eigenvalues().real().minCoeff();
}

Voigt6 aTimes(const Tangent6& a, const Voigt6& e) { return a * e; }

}  // namespace

TwoPhasePoint3D::TwoPhasePoint3D(const EnrichedParams& p)
    : law_((p.validate(), p.band)),
      e_(p.band.elastic.youngsModulus),
      nu_(p.band.elastic.poissonRatio),
      bandWidth_(p.bandWidth),
      stiffness_(isotropicStiffness3(e_, nu_)),
      onsetBound_(0.5 * std::max(1.0 + nu_, 1.0 - 2.0 * nu_) / e_),
      shearModulus_(stiffness_(3, 3)),
      acousticRatio_((stiffness_(0, 1) + stiffness_(3, 3)) / stiffness_(0, 0)) {
  if (p.secondBand != SecondBandOption::Off)
    throw ParameterError(std::string("second_band: ") + toString(p.secondBand) +
                         " is not offered in 3D: a second band needs a normal chosen among the directions of the "
                         "first band's plane, which the 2D rule (the band's tangent) does not fix (docs/model.md)", "second_band");
}

BandResponse3 TwoPhasePoint3D::evaluateBand(const BandDamageLaw::LoadingSurface& surface, const Voigt6& strain,
                                            bool loadingTangent) const {
  BandResponse3 r;
  const Voigt6 effective = stiffness_ * strain;
  const DrivingForce3 y = drivingForce3(effective, e_, nu_);  // Eq. (12)
  r.drivingForce = y.value;
  const BandDamageLaw::IntegrityResponse x = law_.integrityFor(surface, y.value, loadingTangent);  // Eq. (13)
  r.loading = x.loading;
  r.integrity = x.integrity;
  r.stress = r.integrity * effective;  // Eq. (11)
  if (x.loadingTangent) {  // dx/deps = (dx/dY) (dY/dsigma) a
    const Eigen::Matrix<double, 1, 6> dxde = x.dxdy * (y.stressGradient.transpose() * stiffness_);
    r.tangent = r.integrity * stiffness_ + effective * dxde;
  } else {
    r.tangent = r.integrity * stiffness_;
  }
  return r;
}

BandEquilibrium3 TwoPhasePoint3D::equilibrium(const BandState3& b, const BandDamageLaw::LoadingSurface& surface,
                                              const Voigt6& strain, const Vec3& jump, bool loadingTangent) const {
  const JumpMap3 N = jumpToStrain3(b.crackNormal);
  const double f = b.volumeFraction;
  BandEquilibrium3 eq;
  eq.bandStrain = b.onsetStrain + N * jump / bandWidth_;                                            // Eq. (3)
  eq.band = evaluateBand(surface, eq.bandStrain, loadingTangent);                                  // Eqs. (5), (11)-(13)
  eq.stress = stiffness_ * (strain - f * eq.bandStrain) / (1.0 - f);                               // Eqs. (2), (4)
  eq.residual = N.transpose() * (eq.stress - eq.band.stress);                                      // Eq. (6)
  eq.jacobian = N.transpose() * (f / (1.0 - f) * stiffness_ + eq.band.tangent) * N / bandWidth_;   // Eq. (9)
  return eq;
}

Mat3 TwoPhasePoint3D::secantJacobian(const BandState3& b, double x) const {
  const JumpMap3 N = jumpToStrain3(b.crackNormal);
  const double f = b.volumeFraction;
  return N.transpose() * ((f / (1.0 - f) + x) * stiffness_) * N / bandWidth_;  // Eq. (9), a_L = x a
}

Tangent6 TwoPhasePoint3D::consistentTangent(const BandState3& b, const Mat3& jacobian) const {
  const JumpMap3 N = jumpToStrain3(b.crackNormal);
  const double f = b.volumeFraction;
  const Eigen::Matrix<double, 3, 6> dJumpdStrain = jacobian.inverse() * N.transpose() * stiffness_ / (1.0 - f);  // Eq. (8)
  return stiffness_ / (1.0 - f) * (Tangent6::Identity() - f / bandWidth_ * N * dJumpdStrain);                    // Eq. (10)
}

Voigt6 TwoPhasePoint3D::stress(const BandState3& b, const Voigt6& strain) const {
  return equilibrium(b, law_.loadingSurface(b.integrity), strain, b.jump, false).stress;
}

double TwoPhasePoint3D::storedEnergy(const BandState3& b, const Voigt6& strain) const {
  const BandEquilibrium3 eq = equilibrium(b, law_.loadingSurface(b.integrity), strain, b.jump, false);
  const double f = b.volumeFraction;
  const Voigt6 bulkStrain = (strain - f * eq.bandStrain) / (1.0 - f);  // Eq. (2)
  return 0.5 * ((1.0 - f) * eq.stress.dot(bulkStrain) + f * eq.band.stress.dot(eq.bandStrain));
}

std::optional<double> TwoPhasePoint3D::onsetFraction(const Voigt6& strain, const Voigt6& increment) const {
  const double yOnset = law_.onsetDrivingForce();
  return onsetFractionOf([&](double a) { return drivingForceValue3(aTimes(stiffness_, strain + a * increment), e_, nu_) - yOnset; },
                         yOnset);
}

Vec3 TwoPhasePoint3D::onsetNormal(const Voigt6& strain) const {
  return canonicalNormal3(largestPrincipal(stiffness_ * strain).firstDirection);
}

UpdateResult3 TwoPhasePoint3D::updateIntactSlow(Voigt6& strain, const Voigt6& increment, const EffectiveSize3& size,
                                                std::optional<BandState3>& onset, UpdateOptions options) const {
  UpdateResult3 r;
  r.stress = stiffness_ * (strain + increment);
  r.tangent = stiffness_;
  const std::optional<double> alpha = onsetFraction(strain, increment);
  if (!alpha) {
    strain += increment;
    return r;
  }
  BandState3 b;
  b.onsetStrain = strain + *alpha * increment;
  b.crackNormal = onsetNormal(b.onsetStrain);
  const double effectiveSize = size(b.crackNormal);
  if (!(effectiveSize >= minimumEffectiveSize(bandWidth_))) {  // H <= h leaves no bulk (docs/model.md)
    r.status = UpdateStatus::SizeTooSmall;
    r.refusedSize = effectiveSize;
    return r;
  }
  b.volumeFraction = bandWidth_ / effectiveSize;  // Eq. (1)
  Voigt6 cracked = b.onsetStrain;
  r = updateCracked(b, cracked, (1.0 - *alpha) * increment, options);
  if (r.converged()) {
    strain = cracked;
    onset = b;
  }
  return r;
}

UpdateResult3 TwoPhasePoint3D::updateCracked(BandState3& b, Voigt6& strain, const Voigt6& increment,
                                             UpdateOptions options) const {
  UpdateResult3 r = predictCorrect(b, strain, increment, options.tangent, options.stressControlled);
  if (r.converged() || options.snapBack != SnapBackPolicy::Release) return r;
  if (r.status == UpdateStatus::SnapBack) return releaseSnapBack(b, strain, increment, options.tangent);
  // A stalled Newton: the release's scan in x may find the consistent state (as in 2D).
  const UpdateResult3 released = releaseSnapBack(b, strain, increment, options.tangent);
  return released.converged() ? released : r;
}

UpdateResult3 TwoPhasePoint3D::releaseSnapBack(BandState3& b, Voigt6& strain, const Voigt6& increment,
                                               bool tangent) const {
  const Voigt6 eps = strain + increment;
  const double f = b.volumeFraction;
  // With the damage frozen at x, Eq. (6) is linear in [u]: g(x) = Y([u](x)) / F(x) - 1 changes
  // sign between x0 (g > 0) and x -> 0. Scan x down, solve each bracket in log x, keep the first
  // root the regular update confirms stable.
  struct Probe {
    double g;
    BandState3 band;
  };
  const auto probe = [&](double x) {
    Probe p{0.0, b};
    p.band.integrity = x;
    const BandDamageLaw::LoadingSurface frozen{x, std::numeric_limits<double>::infinity()};
    const BandEquilibrium3 eq = equilibrium(p.band, frozen, eps, b.jump, false);
    p.band.jump = b.jump + secantSolve(b, x, eq.residual);
    const BandEquilibrium3 moved = equilibrium(p.band, frozen, eps, p.band.jump, false);
    p.g = moved.band.drivingForce / damageFunction(law_.law(), x) - 1.0;
    return p;
  };
  UpdateResult3 res;
  res.status = UpdateStatus::SnapBack;
  // Polish each root with the regular update at zero increment: it confirms continuity, loading
  // consistency and stability, or reports this root unstable.
  releaseScan(probe, b.integrity, res.iterations, [&](const Probe& root) {
    BandState3 trial = root.band;
    Voigt6 s = eps;
    const UpdateResult3 r = predictCorrect(trial, s, Voigt6::Zero(), tangent, 0);
    const bool isStable =
        r.converged() &&
        positiveDefinite3(equilibrium(trial, law_.envelope(trial.integrity), eps, trial.jump, true).jacobian);
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

double TwoPhasePoint3D::crackedTolerance(const Voigt6& aEps, double f) const {
  return TwoPhasePoint::kRelativeTolerance * tensileStrength() +
         TwoPhasePoint::kRoundOff * aEps.norm() * std::max(1.0, f / (1.0 - f));
}

UpdateResult3 TwoPhasePoint3D::predictCorrect(BandState3& b, Voigt6& strain, const Voigt6& increment, bool tangent,
                                              unsigned stressControlled) const {
  const Voigt6 eps = strain + increment;
  UpdateResult3 res;
  const Voigt6 aEps = stiffness_ * eps;
  const double f = b.volumeFraction;
  const double tol = crackedTolerance(aEps, f);

  // 1. Elastic predictor: the damage frozen at x0, Eq. (6) is linear in [u], solved by the
  //    secant K of Eq. (9) in closed form.
  const JumpMap3 N = jumpToStrain3(b.crackNormal);
  const double x0 = b.integrity;
  Vec3 jump = b.jump;
  Voigt6 aBand = stiffness_ * (b.onsetStrain + N * jump / bandWidth_);                 // a eps_L, Eq. (3)
  const auto stressOf = [&](const Voigt6& aL) -> Voigt6 { return (aEps - f * aL) / (1.0 - f); };  // Eqs. (2), (4)
  Vec3 residual = N.transpose() * (stressOf(aBand) - x0 * aBand);                       // Eqs. (6), (11)
  for (int it = 0; it < 3 && residual.norm() > tol; ++it) {
    jump += secantSolve(b, x0, residual);
    aBand = stiffness_ * (b.onsetStrain + N * jump / bandWidth_);
    residual = N.transpose() * (stressOf(aBand) - x0 * aBand);
    ++res.iterations;
  }
  const double y = drivingForceValue3(aBand, e_, nu_);
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

  // 2. Damage corrector: Newton with line search on the loading envelope (docs/model.md pitfall 2).
  const BandDamageLaw::LoadingSurface envelope = BandDamageLaw::envelope(surface);
  BandEquilibrium3 eq = equilibrium(b, envelope, eps, jump, true);
  double rn = eq.residual.norm();
  bool sawUnstableBranch = false;
  int it = 0;
  for (; rn > tol && it < TwoPhasePoint::kMaxIterations; ++it) {
    const Vec3 step = eq.jacobian.partialPivLu().solve(eq.residual);
    if (!step.allFinite()) break;
    double alpha = 1.0;
    BandEquilibrium3 trial;
    for (int ls = 0; ls < 40; ++ls, alpha *= 0.5) {
      trial = equilibrium(b, envelope, eps, jump + alpha * step, true);
      if (trial.residual.norm() < (1.0 - 1e-4 * alpha) * rn) break;
    }
    jump += alpha * step;
    eq = trial;
    rn = eq.residual.norm();
    sawUnstableBranch = sawUnstableBranch || (eq.band.loading && !positiveDefinite3(eq.jacobian));
  }
  res.iterations += it;
  res.residual = rn;
  res.stress = eq.stress;
  if (!(rn <= tol)) {
    res.status = sawUnstableBranch ? UpdateStatus::SnapBack : UpdateStatus::NotConverged;
    return res;
  }
  if (eq.band.integrity >= b.integrity) {
    if (eq.band.drivingForce < surface.threshold * (1.0 - TwoPhasePoint::kNeutralLoading)) {
      res.status = UpdateStatus::SnapBack;
      return res;
    }
    eq = equilibrium(b, surface, eps, jump, false);  // neutral loading: damage unchanged
  } else if (stressControlled == 0 ? !positiveDefinite3(eq.jacobian)
                                    : !(stabilityMargins(b, eq.jacobian, stressControlled).minCoeff() >
                                        -TwoPhasePoint::kMarginFloor)) {
    res.status = UpdateStatus::SnapBack;
    return res;
  }
  if ((jump - b.jump).norm() > TwoPhasePoint::kJumpCheck * bandWidth_ && !bandHasFailed(b) &&
      firstUnstableOnPath(b, surface, jump, stressControlled)) {
    res.status = UpdateStatus::SnapBack;
    return res;
  }
  res.residual = eq.residual.norm();
  res.stress = eq.stress;
  if (!(res.residual <= tol)) {
    res.status = UpdateStatus::NotConverged;
    return res;
  }
  if (tangent) res.tangent = consistentTangent(b, eq.jacobian);
  res.dissipation = f * law_.dissipation(b.integrity, eq.band.integrity, surface.threshold, eq.band.drivingForce);  // f int Y dD
  b.jump = jump;
  b.integrity = eq.band.integrity;
  strain = eps;
  return res;
}

Eigen::Vector2d TwoPhasePoint3D::stabilityMargins(const BandState3& b, const Mat3& jacobian, unsigned stressControlled) const {
  const double kMargin = smallestRealEigenvalue(jacobian) * bandWidth_ /
                         (shearModulus_ * (b.volumeFraction / (1.0 - b.volumeFraction) + 1.0));
  if (stressControlled == 0 || !(kMargin > 0.0)) return {kMargin, 1.0};
  return {kMargin, stressControlledMargin(consistentTangent(b, jacobian), stressControlled)};
}

double TwoPhasePoint3D::stressControlledMargin(const Tangent6& d, unsigned stressControlled) const {
  std::vector<int> idx;
  for (int i = 0; i < 6; ++i)
    if (stressControlled & (1u << i)) idx.push_back(i);
  const int m = static_cast<int>(idx.size());
  Eigen::MatrixXd block(m, m);
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j) block(i, j) = d(idx[i], idx[j]);
  const double margin = m == 1 ? block(0, 0) : smallestRealEigenvalue(block);
  return margin / e_;
}

bool TwoPhasePoint3D::bandHasFailed(const BandState3& b) const {
  const JumpMap3 N = jumpToStrain3(b.crackNormal);
  const Vec3 traction = b.integrity * (N.transpose() * (stiffness_ * (b.onsetStrain + N * b.jump / bandWidth_)));  // Eq. (11)
  return traction.norm() < TwoPhasePoint::kFailedTraction * tensileStrength();
}

std::optional<double> TwoPhasePoint3D::firstUnstableOnPath(const BandState3& b, const BandDamageLaw::LoadingSurface& surface,
                                                          const Vec3& jump, unsigned stressControlled) const {
  // The 3D port of TwoPhasePoint::firstUnstableOnPath (docs/model.md, "Snap-back on the path").
  const Vec3 delta = jump - b.jump;
  const JumpMap3 N = jumpToStrain3(b.crackNormal);
  const double f = b.volumeFraction;
  const auto margins = [&](double t) {
    const BandResponse3 band = evaluateBand(surface, b.onsetStrain + N * (b.jump + t * delta) / bandWidth_, true);
    const Mat3 k = N.transpose() * (f / (1.0 - f) * stiffness_ + band.tangent) * N / bandWidth_;  // Eq. (9)
    return stabilityMargins(b, k, stressControlled);
  };
  const double floor = -TwoPhasePoint::kMarginFloor;
  const auto crossing = [&](int i, double stable, double unstable) {
    for (int it = 0; it < 50 && unstable - stable > 1e-14; ++it) {
      const double mid = 0.5 * (stable + unstable);
      (margins(mid)[i] > floor ? stable : unstable) = mid;
    }
    return unstable;
  };
  const double length = delta.norm();
  const int uniform = std::clamp(static_cast<int>(std::ceil(length / (TwoPhasePoint::kJumpCheck * bandWidth_))),
                                 TwoPhasePoint::kJumpSamples, TwoPhasePoint::kMaxPathSamples);
  std::vector<double> ts;
  ts.reserve(uniform + 400);
  for (int k = 0; k <= uniform; ++k) ts.push_back(double(k) / uniform);
  for (double t = TwoPhasePoint::kFirstGeometricSample; t < 1.0 / uniform; t *= TwoPhasePoint::kGeometricRatio) ts.push_back(t);
  std::sort(ts.begin(), ts.end());
  const int count = static_cast<int>(ts.size());
  std::vector<Eigen::Vector2d> sampled(count);
  for (int k = 0; k < count; ++k) {
    sampled[k] = margins(ts[k]);
    for (int i = 0; i < 2; ++i)
      if (!(sampled[k][i] > floor)) return k == 0 ? 0.0 : crossing(i, ts[k - 1], ts[k]);
  }
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  std::optional<double> first;
  for (int i = 0; i < (stressControlled ? 2 : 1); ++i) {
    std::vector<int> minima;
    for (int k = 0; k < count; ++k)
      if ((k == 0 || sampled[k][i] <= sampled[k - 1][i]) && (k + 1 == count || sampled[k][i] <= sampled[k + 1][i]))
        minima.push_back(k);
    std::sort(minima.begin(), minima.end(), [&](int a, int c) { return sampled[a][i] < sampled[c][i]; });
    if (minima.size() > TwoPhasePoint::kRefinedMinima) minima.resize(TwoPhasePoint::kRefinedMinima);
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

}  // namespace ecm
