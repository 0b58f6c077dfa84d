#pragma once
// The band's damage law, Eqs. (11)-(13): sigma_L = (1 - D) a_L : eps_L, damage driven by the
// positive part of the effective stress, F(D) of Eq. (13), D irreversible.
#include <cmath>
#include <optional>

#include "material/damage_function.hpp"
#include "material/driving_force.hpp"
#include "material/linear_elastic.hpp"

namespace ecm {

struct BandDamageParams {
  ElasticParams elastic;  // a_L
  double tensileStrength = 0.0;
  double softeningModulus = 0.0;
  double softeningExponent = 0.0;
  void validate() const;
  DamageLawParams law() const {
    return {elastic.youngsModulus, tensileStrength, softeningModulus, softeningExponent};
  }
};

// Response of the law to a total strain, from the integrity at the start of the increment.
struct BandResponse {
  Voigt stress = Voigt::Zero();
  Tangent tangent = Tangent::Zero();  // consistent: spectral split when loading, secant otherwise
  double integrity = 1.0;             // x = 1 - D at the end of the increment
  double drivingForce = 0.0;          // Y
  Eigen::RowVector3d drivingForceRate = Eigen::RowVector3d::Zero();  // dY / d eps_L
  bool loading = false;               // damage grew in this evaluation
};

class BandDamageLaw {
 public:
  struct State {
    double integrity = 1.0;  // x = 1 - D, in (0, 1]
    double damage() const { return 1.0 - integrity; }
  };

  explicit BandDamageLaw(const BandDamageParams& p);

  // The damage threshold at the start of an increment: Y <= F(x0), Eq. (12).
  struct LoadingSurface {
    double integrity;           // x0
    double threshold;           // F(x0)
    bool envelope = false;      // evaluate on the monotonic envelope x = F^-1(Y), also below the surface
    double integrityPower = 0;  // x0^n (0: not computed; only loading evaluations need it)
  };
  LoadingSurface loadingSurface(double integrity) const {
    const double xn = std::pow(integrity, law_.softeningExponent);
    return {integrity, damageFunction(law_, integrity, xn), false, xn};
  }
  // The same surface, but evaluate() follows the monotonic loading envelope: x solves F(x) = Y
  // without the irreversibility cap, with the loading tangent. Smooth across the surface, it is
  // the branch a damage corrector iterates on (no loading/unloading kink inside Newton).
  LoadingSurface envelope(double integrity) const { return envelope(loadingSurface(integrity)); }
  static LoadingSurface envelope(const LoadingSurface& s) { return {s.integrity, s.threshold, true, s.integrityPower}; }

  // The integrity at the end of an increment whose driving force is `y` (Eqs. (12)-(13)), from the
  // surface of its start: loading where Y > F(x0) (x solves F(x) = Y below x0), the healed
  // envelope below the surface when the surface asks for it, x0 otherwise; and dx/dY = 1 / F'(x)
  // where the tangent is the loading one (0 where F' overflows near the underflow limit: the
  // damage then no longer changes the vanishing stress). The scalar part of evaluate(), shared
  // with the 3D point (TwoPhasePoint3D::evaluateBand).
  struct IntegrityResponse {
    double integrity = 1.0;
    bool loading = false;         // damage grew
    bool loadingTangent = false;  // the tangent takes dx/dY
    double dxdy = 0.0;
  };
  IntegrityResponse integrityFor(const LoadingSurface& surface, double y, bool loadingTangent) const;

  // Pure: does not change any state. The surface is that of the start of the increment.
  // With loadingTangent, a point exactly on the loading surface gets the one-sided loading
  // tangent (docs/model.md pitfall 2) instead of the secant.
  BandResponse evaluate(const LoadingSurface& surface, const Voigt& strain, bool loadingTangent = false) const;
  BandResponse evaluate(double integrity, const Voigt& strain, bool loadingTangent = false) const {
    return evaluate(loadingSurface(integrity), strain, loadingTangent);
  }

  // Energy per unit band volume dissipated when x drops from xOld to xNew.
  double dissipation(double xOld, double xNew) const { return dissipationBetween(law_, xOld, xNew); }
  // The same with F(xOld) (the loading surface) and F(xNew) (the driving force Y) known.
  double dissipation(double xOld, double xNew, double fOld, double fNew) const {
    return dissipationBetween(law_, xOld, xNew, fOld, fNew);
  }
  double onsetDrivingForce() const { return onsetY_; }
  // Y of Eq. (12) for an effective stress: the in-plane split in plane stress, the 3D split
  // (sigma_zz = nu (sxx + syy) as the third principal value) in plane strain (docs/model.md).
  double drivingForceValue(const Voigt& effectiveStress) const {
    return planeStrain_ ? drivingForcePlaneStrainValue(effectiveStress, law_.youngsModulus, nu_)
                        : ecm::drivingForceValue(effectiveStress, compliance_);
  }
  DrivingForce drivingForceOf(const Voigt& effectiveStress) const {
    return planeStrain_ ? drivingForcePlaneStrain(effectiveStress, law_.youngsModulus, nu_)
                        : drivingForce(effectiveStress, compliance_);
  }
  // b with Y <= b (sxx^2 + syy^2 + 2 sxy^2) for every effective stress: a cheap no-onset test.
  double drivingForceBound() const { return drivingForceBound_; }
  // Fraction alpha in [0, 1] of a strain increment at which the undamaged law first meets the
  // onset criterion, Eq. (12) with D = 0; nullopt if it is not met within the increment.
  std::optional<double> onsetFraction(const Voigt& strain, const Voigt& strainIncrement) const;  // F(D = 0) = f_t'^2 / (2E)
  const DamageLawParams& law() const { return law_; }
  const Tangent& stiffness() const { return stiffness_; }
  const Tangent& compliance() const { return compliance_; }

 private:
  DamageLawParams law_;
  Tangent stiffness_;
  Tangent compliance_;
  double onsetY_;
  bool planeStrain_;
  double nu_;
  double drivingForceBound_;
};

}  // namespace ecm
