#include "material/band_damage_law.hpp"
#include "material/band_onset.hpp"

#include <algorithm>
#include <cmath>

#include "material/driving_force.hpp"

namespace ecm {

void BandDamageParams::validate() const {
  elastic.validate();
  law().validate();
}

BandDamageLaw::BandDamageLaw(const BandDamageParams& p)
    : law_((p.validate(), p.law())),
      stiffness_(elasticStiffness(p.elastic)),
      compliance_(elasticCompliance(p.elastic)),
      onsetY_(damageFunction(law_, 1.0)),
      planeStrain_(p.elastic.hypothesis == Hypothesis::PlaneStrain),
      nu_(p.elastic.poissonRatio),
      // plane stress: the largest eigenvalue of the 2D compliance / 2; plane strain: that of the
      // 3D compliance / 2 times |sigma+|^2 <= (1 + 2 nu^2) (p1^2 + p2^2) with p3 = nu (p1 + p2)
      drivingForceBound_(planeStrain_ ? 0.5 * std::max(1.0 + nu_, 1.0 - 2.0 * nu_) * (1.0 + 2.0 * nu_ * nu_) / law_.youngsModulus
                                      : 0.5 * (compliance_(0, 0) + std::abs(compliance_(0, 1)))) {}

BandDamageLaw::IntegrityResponse BandDamageLaw::integrityFor(const LoadingSurface& surface, double y, bool loadingTangent) const {
  const double x0 = surface.integrity, threshold = surface.threshold;
  IntegrityResponse r;
  r.loading = y > threshold;
  PoweredIntegrity x{x0, 0.0};
  if (r.loading)
    x = solveIntegrity(law_, y, {x0, surface.integrityPower > 0.0 ? surface.integrityPower : std::pow(x0, law_.softeningExponent)});
  else if (surface.envelope && y > onsetY_)
    x = solveIntegrity(law_, y, {1.0, 1.0});  // below the surface: the healed envelope
  else if (surface.envelope)
    x = {1.0, 1.0};
  r.integrity = x.x;
  const bool onSurface = y >= threshold * (1.0 - 1e-12) && y > 0.0;
  const bool onEnvelope = surface.envelope && y > onsetY_;
  r.loadingTangent = (r.loading || onEnvelope || (loadingTangent && onSurface)) && r.integrity > 0.0;
  if (r.loadingTangent) {
    // dx/dY = 1 / F'(x). At an integrity near the underflow limit, dF/dx overflows (x^(n-1)); the
    // damage then no longer changes the (vanishing) stress: its contribution to the tangent is zero.
    const double slope = x.xn > 0.0 ? damageFunctionSlope(law_, r.integrity, x.xn) : damageFunctionSlope(law_, r.integrity);
    r.dxdy = std::isfinite(slope) && slope != 0.0 ? 1.0 / slope : 0.0;
  }
  return r;
}

BandResponse BandDamageLaw::evaluate(const LoadingSurface& surface, const Voigt& strain, bool loadingTangent) const {
  BandResponse r;
  const Voigt effective = stiffness_ * strain;
  const DrivingForce y = drivingForceOf(effective);  // Eq. (12)
  r.drivingForce = y.value;
  r.drivingForceRate = y.stressGradient.transpose() * stiffness_;
  const IntegrityResponse x = integrityFor(surface, y.value, loadingTangent);  // Eq. (13)
  r.loading = x.loading;
  r.integrity = x.integrity;
  r.stress = r.integrity * effective;  // Eq. (11)
  if (x.loadingTangent) {
    // dx/deps = (dx/dY) (dY/dsigma) a
    const Eigen::RowVector3d dxde = x.dxdy * r.drivingForceRate;
    r.tangent = r.integrity * stiffness_ + effective * dxde;
  } else {
    r.tangent = r.integrity * stiffness_;
  }
  return r;
}

std::optional<double> BandDamageLaw::onsetFraction(const Voigt& strain, const Voigt& increment) const {
  return onsetFractionOf([&](double a) { return drivingForceValue(stiffness_ * (strain + a * increment)) - onsetY_; }, onsetY_);
}

}  // namespace ecm
