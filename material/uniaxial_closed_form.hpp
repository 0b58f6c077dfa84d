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
  double opening;     // w = h (eps_L,nn - sigma/E), the inelastic opening (MODEL-NOTES pitfall 4)
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

// Macro strain of a point of effective size H at that state: eps = sigma/E + w/H.
inline double uniaxialMacroStrain(const UniaxialBandPoint& p, double youngsModulus, double effectiveSize) {
  return p.stress / youngsModulus + p.opening / effectiveSize;
}

}  // namespace ecm
