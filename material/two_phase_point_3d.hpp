#pragma once
// The enriched two-phase material point in 3D (docs/model.md, "The point in 3D"): Eqs. (1)-(10)
// with six strain components, a band normal in space and a jump of three components; the band
// obeys the damage law of Eqs. (11)-(13) with Y over the three principal values of its effective
// stress. The same algorithm as the 2D point (material/two_phase_point.hpp): elastic predictor,
// damage corrector on the loading envelope, snap-back on the path, release, Eq. (10).
// One band: a second band is refused in 3D (EnrichedParams::secondBand must be Off).
#include <optional>

#include "material/band_damage_law.hpp"
#include "material/driving_force_3d.hpp"
#include "material/effective_size_3d.hpp"
#include "material/two_phase_point.hpp"
#include "material/update_result_3d.hpp"

namespace ecm {

// Everything a cracked 3D point carries; an intact point carries none of it.
struct BandState3 {
  Vec3 crackNormal = Vec3::Zero();      // n, fixed at onset (largest principal direction)
  Vec3 jump = Vec3::Zero();             // [u] accumulated since onset (mm)
  Voigt6 onsetStrain = Voigt6::Zero();  // strain of both phases at onset; eps_L = this + N [u] / h
  double integrity = 1.0;               // x = 1 - D of the band
  double volumeFraction = 0.0;          // f = h / H, Eq. (1)

  double damage() const { return 1.0 - integrity; }
  double normalJump() const { return crackNormal.dot(jump); }
  Vec3 slidingJump() const { return jump - normalJump() * crackNormal; }
};

// The band law's response to a band strain (Eqs. (11)-(13)), from the surface of the increment.
struct BandResponse3 {
  Voigt6 stress = Voigt6::Zero();      // sigma_L = x a eps_L
  Tangent6 tangent = Tangent6::Zero(); // a_L^T: loading (x a + a eps_L dx/deps) or secant (x a)
  double integrity = 1.0;
  double drivingForce = 0.0;           // Y
  bool loading = false;
};

// Both phases at a trial (strain, jump).
struct BandEquilibrium3 {
  Voigt6 bandStrain = Voigt6::Zero();  // eps_L, Eq. (3)
  BandResponse3 band;                  // Eqs. (5), (11)
  Voigt6 stress = Voigt6::Zero();      // the bulk stress, Eq. (4)
  Vec3 residual = Vec3::Zero();        // (sigma - sigma_L) n, Eq. (6): three equations
  Mat3 jacobian = Mat3::Zero();        // K = -d residual / d[u], Eq. (9)
};

class TwoPhasePoint3D {
 public:
  // Throws ParameterError for a second band (not offered in 3D, docs/model.md).
  explicit TwoPhasePoint3D(const EnrichedParams& p);

  // Intact point: elastic, or onset inside the increment (split at the exact onset, Eq. (12)
  // with D = 0); `onset` then receives the band and the rest is taken cracked.
  // (Inline: the elastic case is the common one.)
  UpdateResult3 updateIntact(Voigt6& strain, const Voigt6& strainIncrement, const EffectiveSize3& size,
                             std::optional<BandState3>& onset, UpdateOptions options = {}) const {
    const Voigt6 end = strain + strainIncrement;
    const Voigt6 s = stiffness_ * end;
    // |sigma|^2 from the stress's registers: reading s back from memory straddles two stores,
    // which stalls store forwarding.
    const double squared = s[0] * s[0] + s[1] * s[1] + s[2] * s[2] + 2.0 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]);
    if (onsetBound_ * squared < law_.onsetDrivingForce()) {
      strain = end;  // surely intact: Y <= onsetBound_ |sigma|^2 < F(0)
      // The tangent written once (not zeroed first), by Eigen's unrolled packet copy: an
      // aggregate copy of the 288 bytes became a call to memcpy.
      UpdateResult3 r{s, Tangent6()};
      r.tangent = stiffness_;
      return r;
    }
    return updateIntactSlow(strain, strainIncrement, size, onset, options);
  }
  // Cracked point: predictor-corrector, then the snap-back policy. State unchanged on failure.
  UpdateResult3 updateCracked(BandState3& band, Voigt6& strain, const Voigt6& strainIncrement,
                              UpdateOptions options = {}) const;
  // Snap-back release at the end strain (the 3D port of TwoPhasePoint::releaseSnapBack).
  UpdateResult3 releaseSnapBack(BandState3& band, Voigt6& strain, const Voigt6& strainIncrement, bool tangent) const;

  BandResponse3 evaluateBand(const BandDamageLaw::LoadingSurface& surface, const Voigt6& bandStrain,
                             bool loadingTangent) const;
  BandEquilibrium3 equilibrium(const BandState3& b, const BandDamageLaw::LoadingSurface& surface, const Voigt6& strain,
                               const Vec3& jump, bool loadingTangent) const;
  // Consistent tangent d sigma / d eps at a converged equilibrium with Jacobian K, Eq. (10).
  Tangent6 consistentTangent(const BandState3& b, const Mat3& jacobian) const;
  // K of Eq. (9) with the band's damage frozen at x.
  Mat3 secantJacobian(const BandState3& b, double x) const;
  // The bulk stress and the stored energy (bulk and band, per unit volume) of a committed state.
  Voigt6 stress(const BandState3& b, const Voigt6& strain) const;
  double storedEnergy(const BandState3& b, const Voigt6& strain) const;

  std::optional<double> onsetFraction(const Voigt6& strain, const Voigt6& strainIncrement) const;
  // The crack normal at onset: the largest principal direction of a : strain, canonical sign.
  Vec3 onsetNormal(const Voigt6& strain) const;

  // Snap-back on the path (docs/model.md): the first fraction of the jump segment from b.jump
  // to `jump` where K of Eq. (9), or the stress-controlled block of D (Eq. (10)), stops being
  // positive definite; nullopt if the path stays stable.
  std::optional<double> firstUnstableOnPath(const BandState3& b, const BandDamageLaw::LoadingSurface& surface,
                                            const Vec3& jump, unsigned stressControlled = 0) const;
  // Scaled smallest real eigenvalues of K and of the stress-controlled block of D (> 0: stable).
  Eigen::Vector2d stabilityMargins(const BandState3& b, const Mat3& jacobian, unsigned stressControlled) const;
  double stressControlledMargin(const Tangent6& d, unsigned stressControlled) const;
  bool bandHasFailed(const BandState3& b) const;

  const Tangent6& stiffness() const { return stiffness_; }
  const BandDamageLaw& bandLaw() const { return law_; }
  double bandWidth() const { return bandWidth_; }
  double tensileStrength() const { return law_.law().tensileStrength; }
  double youngsModulus() const { return e_; }
  double poissonRatio() const { return nu_; }

 private:
  UpdateResult3 updateIntactSlow(Voigt6& strain, const Voigt6& strainIncrement, const EffectiveSize3& size,
                                 std::optional<BandState3>& onset, UpdateOptions options) const;
  UpdateResult3 predictCorrect(BandState3& b, Voigt6& strain, const Voigt6& increment, bool tangent,
                               unsigned stressControlled) const;
  double crackedTolerance(const Voigt6& aEps, double f) const;
  // The closed-form solve with the secant K of Eq. (9): n^T a n = mu I + (lambda + mu) n n^T.
  Vec3 secantSolve(const BandState3& b, double x, const Vec3& r) const {
    const double c = bandWidth_ / ((b.volumeFraction / (1.0 - b.volumeFraction) + x) * shearModulus_);
    return c * (r - acousticRatio_ * b.crackNormal.dot(r) * b.crackNormal);
  }

  BandDamageLaw law_;  // the scalar law F(x) of Eq. (13), its inverse and its dissipation
  double e_, nu_, bandWidth_;
  Tangent6 stiffness_;
  double onsetBound_;     // Y <= onsetBound_ |sigma|^2: a cheap no-onset test
  double shearModulus_;   // mu
  double acousticRatio_;  // (lambda + mu) / (lambda + 2 mu)
};

}  // namespace ecm
