#pragma once
// The enriched two-phase material point in 3D (docs/model.md, "The point in 3D"): Eqs. (1)-(10)
// with six strain components, a band normal in space and a jump of three components; the band
// obeys the damage law of Eqs. (11)-(13) with Y over the three principal values of its effective
// stress. The same algorithm as the 2D point (material/two_phase_point.hpp): elastic predictor,
// damage corrector on the loading envelope, snap-back on the path, release, Eq. (10).
// One band: a second band is refused in 3D (EnrichedParams::secondBand must be Off).
#include <optional>

#include "material/band_damage_law.hpp"
#include "material/band_state.hpp"
#include "material/driving_force_3d.hpp"
#include "material/effective_size_3d.hpp"
#include "material/two_phase_point.hpp"
#include "material/update_result_3d.hpp"

namespace ecm {

class TwoPhasePoint3D : public CrackedPoint<SpaceBand, TwoPhasePoint3D> {
 public:
  // The cracked update, the phases at a jump, Eq. (10), snap-back on the path and the release:
  // material/cracked_point.hpp. Below, what is the point in space's own.
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

  BandResponse3 evaluateBand(const BandDamageLaw::LoadingSurface& surface, const Voigt6& bandStrain,
                             bool loadingTangent) const;
  // The bulk stress and the stored energy (bulk and band, per unit volume) of a committed state.
  Voigt6 stress(const BandState3& b, const Voigt6& strain) const;
  double storedEnergy(const BandState3& b, const Voigt6& strain) const;

  std::optional<double> onsetFraction(const Voigt6& strain, const Voigt6& strainIncrement) const;
  // The crack normal at onset: the largest principal direction of a : strain, canonical sign.
  Vec3 onsetNormal(const Voigt6& strain) const;

  double stressControlledMargin(const Tangent6& d, unsigned stressControlled) const;

  const Tangent6& stiffness() const { return stiffness_; }
  const BandDamageLaw& bandLaw() const { return law_; }
  double bandWidth() const { return bandWidth_; }
  double tensileStrength() const { return law_.law().tensileStrength; }
  double youngsModulus() const { return e_; }
  double poissonRatio() const { return nu_; }
  double shearModulus() const { return shearModulus_; }
  // Y of Eq. (12) over the three principal values of the band's effective stress a eps_L.
  double bandDrivingForce(const Voigt6& aBand) const { return drivingForceValue3(aBand, e_, nu_); }
  // The closed-form solve with the secant K of Eq. (9): n^T a n = mu I + (lambda + mu) n n^T.
  Vec3 secantSolve(const BandState3& b, double x, const Vec3& r) const {
    const double c = bandWidth_ / ((b.volumeFraction / (1.0 - b.volumeFraction) + x) * shearModulus_);
    return c * (r - acousticRatio_ * b.crackNormal.dot(r) * b.crackNormal);
  }
  // The release's step to [u](x) at frozen damage x: the closed form (the 2D point factorises K).
  Vec3 secantStep(const BandState3& b, double x, const Vec3& r) const { return secantSolve(b, x, r); }

 private:
  UpdateResult3 updateIntactSlow(Voigt6& strain, const Voigt6& strainIncrement, const EffectiveSize3& size,
                                 std::optional<BandState3>& onset, UpdateOptions options) const;

  BandDamageLaw law_;  // the scalar law F(x) of Eq. (13), its inverse and its dissipation
  double e_, nu_, bandWidth_;
  Tangent6 stiffness_;
  double onsetBound_;     // Y <= onsetBound_ |sigma|^2: a cheap no-onset test
  double shearModulus_;   // mu
  double acousticRatio_;  // (lambda + mu) / (lambda + 2 mu)
};

}  // namespace ecm
