#pragma once
// A cracked enriched point, written once for the plane point (TwoPhasePoint) and the one in space
// (TwoPhasePoint3D): the two phases at a trial jump, Eqs. (2)-(9); the consistent tangent,
// Eq. (10); the elastic predictor and the damage corrector on the loading envelope; snap-back on
// the path (docs/model.md); the release onto the stable branch. Only the dimension differs: Space
// is PlaneBand or SpaceBand (material/band_state.hpp).
//
// Point derives from CrackedPoint<Space, Point> and gives what depends on more than the sizes:
//   stiffness(), bandWidth(), shearModulus(), tensileStrength(), bandLaw()
//   evaluateBand(surface, eps_L, loadingTangent)   sigma_L and a_L of Eqs. (5), (11)-(13)
//   bandDrivingForce(a eps_L)                      Y of Eq. (12), over two or three principal values
//   secantSolve(b, x, r), secantStep(b, x, r)      K^-1 r for the secant K of Eq. (9) at damage x
//   stressControlledMargin(D, stressControlled)
// The members are defined in material/cracked_point_update.hpp and instantiated by each point's .cpp.
#include <optional>

#include "material/band_damage_law.hpp"
#include "material/band_state.hpp"
#include "material/update_options.hpp"

namespace ecm {

template <class Space, class Point>
class CrackedPoint {
 public:
  using Strain = typename Space::Strain;
  using StrainTangent = typename Space::StrainTangent;
  using Jump = typename Space::Jump;
  using JumpJacobian = typename Space::JumpJacobian;
  using JumpMap = typename Space::JumpMap;
  using Band = BandStateIn<Space>;
  using Equilibrium = BandEquilibriumIn<Space>;
  using Result = typename Space::Result;
  using LoadingSurface = BandDamageLaw::LoadingSurface;

  // The cracked update under the snap-back policy: predictor-corrector, then (release) the band
  // fails onto its stable branch where the loading branch turned back. On failure the state is
  // left unchanged.
  Result updateCracked(Band& band, Strain& strain, const Strain& strainIncrement, UpdateOptions options = {}) const;

  // Snap-back release: at the end strain of an increment whose loading branch turned back, the
  // band's damage grows at fixed strain until traction continuity (6) holds with consistent
  // damage (Y = F(x)) on a stable branch: the first such state below x0. Converged with
  // `released` set, or SnapBack if none exists. The stored energy released beyond f int Y dD
  // (the point's share of a dynamic snap) is not tracked by the point.
  Result releaseSnapBack(Band& band, Strain& strain, const Strain& strainIncrement, bool tangent = true) const;

  // Pure evaluation of both phases at a trial jump, the band on `surface` (used by Newton and by
  // opening control).
  Equilibrium equilibrium(const Band& band, const LoadingSurface& surface, const Strain& strain, const Jump& jump,
                          bool loadingTangent) const;
  // Consistent tangent d sigma / d eps at a converged equilibrium with Jacobian K, Eq. (10).
  StrainTangent consistentTangent(const Band& band, const JumpJacobian& jacobian) const;
  // K of Eq. (9) with the band's damage frozen at x (a_L = x a): always positive definite.
  JumpJacobian secantJacobian(const Band& band, double x) const;
  // K of Eq. (9) at a jump, the band on the given loading surface with its loading tangent.
  JumpJacobian loadingJacobian(const Band& band, const LoadingSurface& surface, const Jump& jump) const;

  // Snap-back on the path (docs/model.md): along the loading path from the converged state b to
  // the jump `jump` (a straight segment in jump space, the band on the loading surface of b),
  // the first fraction t in [0, 1] where the state stops being stable under the caller's
  // control (K of Eq. (9), and the stress-controlled block of D of Eq. (10), positive
  // definite): the limit point. nullopt if the path stays stable.
  std::optional<double> firstUnstableOnPath(const Band& b, const LoadingSurface& surface, const Jump& jump,
                                            unsigned stressControlled = 0) const;
  // Both > 0 where the state with this K is stable under the caller's control (scaled,
  // continuous): the smallest real eigenvalue of K, and that of the stress-controlled block of D.
  Eigen::Vector2d stabilityMargins(const Band& b, const JumpJacobian& jacobian, unsigned stressControlled) const;
  // The band's traction at its converged state is below kFailedTraction f_t'.
  bool bandHasFailed(const Band& b) const;
  // The traction tolerance of a cracked update at the elastic stress aEps = a eps.
  double crackedTolerance(const Strain& aEps, double f) const;

  // The band that opens at strain onsetStrain with normal n in a point of effective size H:
  // f = h / H (Eq. (1)), no jump, full integrity; nullopt where H <= h (1 + 1e-6) leaves no bulk
  // (docs/model.md), `refused` then set to SizeTooSmall with the size.
  std::optional<Band> bandAtOnset(const Strain& onsetStrain, const Jump& normal, double effectiveSize, Result& refused) const;

 protected:
  // The cracked update proper: elastic predictor, then damage corrector on the envelope.
  Result predictCorrect(Band& b, Strain& strain, const Strain& increment, bool tangent, unsigned stressControlled = 0) const;

 private:
  const Point& self() const { return static_cast<const Point&>(*this); }
};

}  // namespace ecm
