#pragma once
// Closed-form response of the enriched point in uniaxial tension (plane stress), parameterised by
// the band integrity x on the monotonic branch. With the band strain changing only through the
// jump (Eq. (3)), the band's lateral strain stays at its onset value eps0 = -nu f_t'/E, so the
// band is laterally constrained; for nu = 0 this is the 1D law (sigma = uniaxialStress(x)).
// Used to verify the point driver and to report the snap-back study's deviations.
#include <cmath>

#include "material/damage_function.hpp"

namespace ecm {

struct UniaxialBandPoint {
  double stress;      // sigma_nn = x (a eps_L)_nn (MPa)
  double bandStrain;  // eps_L,nn
  double opening;     // w = h (eps_L,nn - sigma/E), the inelastic opening (docs/model.md pitfall 4)
};

// Both effective principal stresses stay non-negative, so Y = eps_L : a : eps_L / 2 = F(x) (Eq. 12)
// gives eps_L,nn in closed form; then sigma from Eq. (11).
inline UniaxialBandPoint uniaxialBandResponse(const DamageLawParams& law, double nu, double bandWidth, double x) {
  const double e = law.youngsModulus, eps0 = -nu * law.tensileStrength / e;
  const double ePrime = e / (1.0 - nu * nu);
  const double y = damageFunction(law, x);
  const double normal = -nu * eps0 + std::sqrt(nu * nu * eps0 * eps0 - eps0 * eps0 + 2.0 * y / ePrime);
  const double stress = x * ePrime * (normal + nu * eps0);
  return {stress, normal, bandWidth * (normal - stress / e)};
}

// Uniaxial strain (eps_yy = gamma_xy = 0): the band's strain is (e, 0, 0), both effective
// principal stresses are positive, Y = a11 e^2 / 2 = F(x) (Eq. 12) and sigma_xx = x a11 e
// (Eq. 11), with a11 the in-plane stiffness's first entry. Here w = h (e - sigma / a11), and
// the macro strain is eps = sigma / a11 + w / H (Eqs. (2)-(4)).
inline UniaxialBandPoint uniaxialStrainBandResponse(const DamageLawParams& law, double a11, double bandWidth, double x) {
  const double e = std::sqrt(2.0 * damageFunction(law, x) / a11);
  const double stress = x * a11 * e;
  return {stress, e, bandWidth * (e - stress / a11)};
}

// The effective size beyond which the macro curve eps = sigma / modulus + w / H turns back
// (snap-back under strain control): modulus / max(-d sigma / d w) over the band's curve
// `curve(x)` (a UniaxialBandPoint of the integrity x); infinity if the curve never softens.
// Scanned in log x, then the steepest stretch refined by golden section.
template <class Curve>
double snapBackEffectiveSize(const Curve& curve, double modulus) {
  const auto slope = [&](double lx) {  // -d sigma / d w at x = 10^lx, central difference in lx
    const double d = 1e-6;
    const UniaxialBandPoint a = curve(std::pow(10.0, lx + d)), b = curve(std::pow(10.0, lx - d));
    return b.opening > a.opening ? -(b.stress - a.stress) / (b.opening - a.opening) : 0.0;
  };
  double best = 0.0, at = 0.0;
  for (double lx = -1e-5; lx > -14.0; lx -= 0.01)
    if (const double s = slope(lx); s > best) best = s, at = lx;
  if (!(best > 0.0)) return INFINITY;
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  double lo = at - 0.01, hi = std::min(at + 0.01, -2e-6);
  for (int it = 0; it < 60; ++it) {
    const double a = hi - g * (hi - lo), b = lo + g * (hi - lo);
    if (slope(a) > slope(b)) hi = b;
    else lo = a;
  }
  return modulus / std::max(best, slope(0.5 * (lo + hi)));
}

// Macro strain of a point of effective size H at that state: eps = sigma/E + w/H.
inline double uniaxialMacroStrain(const UniaxialBandPoint& p, double youngsModulus, double effectiveSize) {
  return p.stress / youngsModulus + p.opening / effectiveSize;
}

}  // namespace ecm
