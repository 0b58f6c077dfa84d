#pragma once
// The enriched two-phase material point, Eqs. (1)-(10): an elastic bulk with an embedded
// localization band of width h (bandWidth) inside the effective size H (effectiveSize),
// f = h/H (volumeFraction). The band obeys the damage law of Eqs. (11)-(13); traction
// continuity (6) couples the phases. Before onset the point is elastic and has no band state.
#include <optional>
#include <string>

#include "material/band_damage_law.hpp"
#include "material/band_state.hpp"
#include "material/cracked_point.hpp"
#include "material/driving_force.hpp"
#include "material/effective_size.hpp"
#include "material/snap_back_policy.hpp"
#include "material/secant_response.hpp"

namespace ecm {

// The smallest effective size the enriched point accepts: H >= h (1 + kMinimumSizeMargin).
// Below it the bulk (volume fraction 1 - f ~ 1e-6) is so thin that the round-off of the macro
// strain, amplified by 1 / (1 - f) in Eq. (4), exceeds the stress tolerances (docs/model.md).
inline constexpr double kMinimumSizeMargin = 1e-6;
// A point that may open a second band needs room for both: twice that (docs/model.md).
inline double minimumEffectiveSize(double bandWidth, int bands = 1) { return bands * bandWidth * (1.0 + kMinimumSizeMargin); }
// Why an effective size is refused ("" if it is accepted), for the scene readers' messages.
std::string effectiveSizeProblem(double effectiveSize, double bandWidth, int bands = 1);

// Whether a cracked point may open a second band across its first band's tangent
// (docs/model.md, "A second band"). Off is the paper's model, bit for bit.
enum class SecondBandOption { Off, Orthogonal };
const char* toString(SecondBandOption o);

struct EnrichedParams {
  BandDamageParams band;    // elastic constants (shared by bulk and band) and the band's damage law
  double bandWidth = 0.0;   // h (mm)
  SecondBandOption secondBand = SecondBandOption::Off;
  void validate() const;
};

struct EnrichedState {
  Voigt strain = Voigt::Zero();         // macroscopic strain
  std::optional<BandState> band;        // present once the point has cracked
  std::optional<BandState> secondBand;  // present once it has opened a second band (option on)
};

using Vec4 = Eigen::Vector4d;
using Mat4 = Eigen::Matrix4d;

// Both bands and the bulk of a two-band point at trial jumps ([u]_1, [u]_2) (docs/model.md,
// "A second band"): Eqs. (2)-(9) with eps = f1 eps_L1 + f2 eps_L2 + (1 - f1 - f2) eps_b.
struct TwoBandEquilibrium {
  Voigt bandStrain[2] = {Voigt::Zero(), Voigt::Zero()};  // eps_Li, Eq. (3) for each band
  BandResponse band[2];                                  // sigma_Li and a_Li, Eqs. (5), (11)
  Voigt stress = Voigt::Zero();                          // the bulk stress, Eq. (4)
  Vec4 residual = Vec4::Zero();                          // (sigma - sigma_Li) n_i, Eq. (6) on each band
  Mat4 jacobian = Mat4::Zero();                          // K = -d residual / d([u]_1, [u]_2), Eq. (9)
};

class TwoPhasePoint : public CrackedPoint<PlaneBand, TwoPhasePoint> {
 public:
  // The one-band cracked update, the phases at a jump, Eq. (10), snap-back on the path and the
  // release: material/cracked_point.hpp. Below, what is the plane point's own.
  using CrackedPoint::consistentTangent;
  using CrackedPoint::equilibrium;
  using CrackedPoint::updateCracked;

  explicit TwoPhasePoint(const EnrichedParams& p);

  // The UMAT-style update of a point. On failure the state is left unchanged.
  UpdateResult update(EnrichedState& state, const Voigt& strainIncrement, const EffectiveSize& size,
                      UpdateOptions options = {}) const;

  // The two halves of update(), for callers (MPM) that keep band states in a side array.
  // Intact point: elastic, or onset inside the increment; then `onset` receives the new band
  // state and the rest of the increment is taken cracked.
  UpdateResult updateIntact(Voigt& strain, const Voigt& strainIncrement, const EffectiveSize& size,
                            std::optional<BandState>& onset, UpdateOptions options = {}) const {
    const Voigt end = strain + strainIncrement;
    const Voigt s = stiffness() * end;
    if (surelyIntact(s)) {
      strain = end;
      return {s, stiffness()};
    }
    return updateIntactSlow(strain, strainIncrement, size, onset, options, nullptr);
  }
  // A cheap sufficient test that the elastic stress s cannot reach onset:
  // Y <= (c11 + |c12|)/2 |sigma|^2 < F(D = 0). Most intact updates stop here, as cheap as elastic
  // (explicit MPM calls it inline, without building an UpdateResult).
  bool surelyIntact(const Voigt& s) const {
    return onsetBound_ * (s[0] * s[0] + s[1] * s[1] + 2.0 * s[2] * s[2]) < law_.onsetDrivingForce();
  }
  // Whether an intact point whose elastic stress ends its increment at s stays intact: the cheap
  // bound, else Y(s) < F(D = 0) of Eq. (12) itself: the test onsetFraction() makes first, so a
  // point that passes it would take no other path through updateIntact() either.
  bool staysIntact(const Voigt& s) const {
    return surelyIntact(s) || law_.drivingForceValue(s) < law_.onsetDrivingForce();
  }
  // The same with the band's secant response kept by the caller (an explicit solver, one per
  // band; material/secant_response.hpp): rebuilt when it is not the band's, then an unloading
  // increment takes it instead of the predictor's solve (the same state to round-off); a
  // loading one takes updateCracked() above, bit for bit. Without the tangent only.
  UpdateResult updateCracked(BandState& band, SecantResponse& secant, Voigt& strain, const Voigt& strainIncrement,
                             UpdateOptions options = {}) const;
  // The secant response of band state b (pure).
  SecantResponse secantResponse(const BandState& b) const;

  // The cracked update of a point under the second-band option (docs/model.md, "A second
  // band"). `second` is the point's second band, nullptr while it has none; a second band that
  // opens inside this increment (the increment is split at its exact onset) is returned in
  // `secondOnset`. With the option off this is updateCracked(first, strain, increment, options).
  UpdateResult updateCracked(BandState& first, BandState* second, Voigt& strain, const Voigt& strainIncrement,
                             const EffectiveSize& size, std::optional<BandState>& secondOnset,
                             UpdateOptions options = {}) const;
  // An intact point under the option: updateIntact, and a second band that opens in the same
  // increment is returned in `secondOnset`.
  UpdateResult updateIntact(Voigt& strain, const Voigt& strainIncrement, const EffectiveSize& size,
                            std::optional<BandState>& onset, std::optional<BandState>& secondOnset,
                            UpdateOptions options = {}) const;
  // The update of a point with two bands: elastic predictor with both damages frozen, then
  // Newton with the loading bands on their envelopes, the active set rechecked until it holds.
  UpdateResult updateTwoBands(BandState& first, BandState& second, Voigt& strain, const Voigt& strainIncrement,
                              UpdateOptions options = {}) const;
  bool opensSecondBand() const { return secondBand_ == SecondBandOption::Orthogonal; }
  // sigma_tt = t1 . sigma t1, the bulk stress along the first band's tangent: the second band
  // opens where it reaches secondBandOnsetStress() (Eq. (12) with D = 0 for sigma_tt t1 (x) t1).
  double tangentialStress(const BandState& first, const Voigt& stress) const;
  double secondBandOnsetStress() const { return secondOnsetStress_; }
  // A second band opening at the converged one-band state (first, strain): normal t1, no jump,
  // eps_L2 = the bulk strain (the stress stays continuous), f2 = h / H(t1). The cracked update
  // refuses it (UpdateStatus::SizeTooSmall) where 1 - f1 - f2 leaves no bulk.
  BandState openSecondBand(const BandState& first, const Voigt& strain, const EffectiveSize& size) const;
  // Pure evaluation of both bands and the bulk at trial jumps, each band on its own surface.
  TwoBandEquilibrium equilibrium(const BandState& first, const BandState& second,
                                 const BandDamageLaw::LoadingSurface (&surfaces)[2], const Voigt& strain,
                                 const Vec4& jumps, bool loadingTangent) const;
  // Consistent tangent of a two-band point at a converged equilibrium (Eq. (10) extended).
  Tangent consistentTangent(const BandState& first, const BandState& second, const Mat4& jacobian) const;
  // The stress of a two-band point at its committed state.
  Voigt stress(const BandState& first, const BandState& second, const Voigt& strain) const;
  // The elastic energy a cracked point stores per unit volume (MPa) at a committed state: the
  // bulk's (1 - f1 - f2) 1/2 eps_b : a : eps_b and each band's f_i 1/2 x_i eps_Li : a : eps_Li
  // (Eqs. (1)-(4), (11)); `second` is nullptr for one band. What a jump at fixed strain
  // releases (docs/model.md, "A second band").
  double storedEnergy(const BandState& first, const BandState* second, const Voigt& strain) const;


  // Both phases at a trial jump, the band on its own loading surface.
  BandEquilibrium equilibrium(const BandState& band, const Voigt& strain, const Vec2& jump,
                              bool loadingTangent) const {
    return equilibrium(band, law_.loadingSurface(band.integrity), strain, jump, loadingTangent);
  }
  // Eq. (10) at a converged equilibrium.
  Tangent consistentTangent(const BandState& band, const BandEquilibrium& eq) const {
    return consistentTangent(band, eq.jacobian);
  }
  // The secant tangent: Eq. (10) with the band's damage frozen at its integrity (the unloading
  // response). An implicit solver uses it where the consistent one makes Newton cycle.
  Tangent secantTangent(const BandState& band) const { return consistentTangent(band, secantJacobian(band, band.integrity)); }

  // Fraction alpha in (0, 1] of the increment at which the onset criterion, Eq. (12) with
  // D = 0, is first met; nullopt if it is not met within the increment.
  std::optional<double> onsetFraction(const Voigt& strain, const Voigt& strainIncrement) const;
  // Damage driving force of the intact point's stress (onset when >= onsetDrivingForce()).
  double intactDrivingForce(const Voigt& strain) const;

  const BandDamageLaw& bandLaw() const { return law_; }
  const Tangent& stiffness() const { return law_.stiffness(); }
  double bandWidth() const { return bandWidth_; }
  double tensileStrength() const { return law_.law().tensileStrength; }
  double shearModulus() const { return shearModulus_; }
  // The band law at a band strain, Eqs. (5), (11)-(13); Y of Eq. (12) at the band's a eps_L.
  BandResponse evaluateBand(const BandDamageLaw::LoadingSurface& surface, const Voigt& bandStrain, bool loadingTangent) const {
    return law_.evaluate(surface, bandStrain, loadingTangent);
  }
  double bandDrivingForce(const Voigt& aBand) const { return law_.drivingForceValue(aBand); }

  // The smallest real eigenvalue of the stress-controlled block of a consistent tangent D
  // (Eq. (10)), scaled by E: > 0 where mixed control has a stable branch (docs/model.md).
  double stressControlledMargin(const Tangent& d, unsigned stressControlled) const;

  // The solve with the secant K of Eq. (9) in closed form: n^T a n = mu I + (lambda + mu) n n^T
  // for the isotropic a, so K^-1 r = h / (f / (1 - f) + x) / mu [r - (lambda + mu) / (lambda + 2 mu) n (n . r)].
  Vec2 secantSolve(const BandState& b, double x, const Vec2& r) const {
    const double c = bandWidth_ / ((b.volumeFraction / (1.0 - b.volumeFraction) + x) * shearModulus_);
    return c * (r - acousticRatio_ * b.crackNormal.dot(r) * b.crackNormal);
  }
  // The release's step to [u](x) at frozen damage x: K^-1 r through K's factorisation (the 3D
  // point takes the closed form; both agree to round-off).
  Vec2 secantStep(const BandState& b, double x, const Vec2& r) const { return secantJacobian(b, x).llt().solve(r); }

  static constexpr int kMaxIterations = 60;
  static constexpr double kRelativeTolerance = 1e-10;  // |residual| <= this * f_t' + kRoundOff |a eps|
  static constexpr double kRoundOff = 1e-13;
  // Loading increments whose jump exceeds kJumpCheck h are checked for a passed limit point:
  // the stability margins sampled every kJumpCheck h along the path (at least kJumpSamples, at
  // most kMaxPathSamples samples) and geometrically closer towards its start, then minimised
  // next to the smallest kRefinedMinima local minima of the samples.
  static constexpr double kJumpCheck = 1e-3;
  static constexpr int kJumpSamples = 8;
  static constexpr int kMaxPathSamples = 256;
  static constexpr double kFirstGeometricSample = 1e-7;  // then x kGeometricRatio up to the first uniform one
  static constexpr double kGeometricRatio = 1.1;
  // A band whose traction is below kFailedTraction f_t' at the start of an increment has
  // failed: no snap-back can drop the stress by more than that, and its path is not checked.
  static constexpr double kFailedTraction = 1e-6;
  static constexpr std::size_t kRefinedMinima = 3;
  // A scaled stability margin above -kMarginFloor is stable: a failed band is neutral in
  // shear (its margin tends to 0), and round-off must not make that a snap-back.
  static constexpr double kMarginFloor = 1e-9;
  // A corrector root this close below the loading surface (relative in Y; the traction
  // tolerance allows ~2e-10) is neutral loading, not a healed band.
  static constexpr double kNeutralLoading = 1e-8;

 private:
  // The two-band release: the damage of the band that snapped back is scanned down at the
  // end strain (the other band follows its own law) to the first stable consistent state.
  UpdateResult releaseTwoBands(BandState& first, BandState& second, Voigt& strain, const Voigt& increment,
                               bool tangent) const;
  // The loading branch of two bands at `eps`, from the jumps `jumps`, with the given bands
  // loading (on their envelopes) and the others frozen at their integrity.
  struct TwoBandSolve {
    TwoBandEquilibrium eq;
    Vec4 jumps = Vec4::Zero();
    bool converged = false;
    bool sawUnstableBranch = false;
    int iterations = 0;
  };
  TwoBandSolve solveTwoBands(const BandState& first, const BandState& second,
                             const BandDamageLaw::LoadingSurface (&surfaces)[2], const Voigt& eps, Vec4 jumps,
                             double tol) const;
  double twoBandTolerance(const BandState& first, const BandState& second, const Voigt& eps) const;
  // The smaller stability margin of a two-band state (> 0: stable under the caller's control).
  double twoBandMargin(const BandState& first, const BandState& second, const Mat4& jacobian,
                       unsigned stressControlled) const;
  UpdateResult updateIntactSlow(Voigt& strain, const Voigt& strainIncrement, const EffectiveSize& size,
                                std::optional<BandState>& onset, UpdateOptions options,
                                std::optional<BandState>* secondOnset) const;

  BandDamageLaw law_;
  double bandWidth_;
  double onsetBound_;  // (c11 + |c12|)/2: Y <= onsetBound_ |sigma|^2, a cheap no-onset test
  double shearModulus_;   // mu = a_33 (in-plane isotropic a: a_11 = lambda + 2 mu, a_12 = lambda)
  double acousticRatio_;  // (lambda + mu) / (lambda + 2 mu)
  SecondBandOption secondBand_;
  double secondOnsetStress_;  // sigma_tt at which Eq. (12) with D = 0 is met: sqrt(2 F(1) / c11)
};

}  // namespace ecm
