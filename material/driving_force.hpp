#pragma once
// The damage driving force of Eq. (12): Y = 1/2 sigma+ : a^-1 : sigma+ of the effective stress
// sigma = a : eps, with sigma+ its positive part from the eigen-decomposition.
#include <algorithm>
#include <cmath>

#include "material/voigt.hpp"

namespace ecm {

struct DrivingForce {
  double value = 0.0;                   // Y (MPa)
  Voigt stressGradient = Voigt::Zero(); // dY/d sigma as a Voigt row: dY = g . d(sigma_voigt)
};

// `compliance` is the (isotropic) in-plane a^-1 of plane stress (plane strain takes
// drivingForcePlaneStrain below, docs/model.md). Because Y is a symmetric function of the principal stresses, its gradient is
// sum_i dY/dp_i (n_i (x) n_i), well defined also at repeated principal stresses.
DrivingForce drivingForce(const Voigt& effectiveStress, const Tangent& compliance);

// Y alone (no principal directions): the same value, bit for bit, as drivingForce().value.
inline double drivingForceValue(const Voigt& s, const Tangent& c) {
  const double mean = 0.5 * (s[0] + s[1]);
  const double halfDiff = 0.5 * (s[0] - s[1]);
  const double radius = std::sqrt(halfDiff * halfDiff + s[2] * s[2]);
  const double p1 = std::max(mean + radius, 0.0), p2 = std::max(mean - radius, 0.0);
  return 0.5 * (c(0, 0) * (p1 * p1 + p2 * p2) + 2.0 * c(0, 1) * p1 * p2);  // Eq. (12)
}

// Y of Eq. (12) from three principal values (any order) and the isotropic (E, nu).
inline double drivingForceOfPrincipal(double p1, double p2, double p3, double youngsModulus, double nu) {
  p1 = p1 > 0.0 ? p1 : 0.0, p2 = p2 > 0.0 ? p2 : 0.0, p3 = p3 > 0.0 ? p3 : 0.0;
  return 0.5 / youngsModulus * (p1 * p1 + p2 * p2 + p3 * p3 - 2.0 * nu * (p1 * p2 + p2 * p3 + p1 * p3));
}

// Plane strain: Eq. (12) over the three principal values of the effective stress, the
// out-of-plane one sigma_zz = nu (sxx + syy), the 3D split (docs/model.md, "The point in 3D").
// Equal to the in-plane form with the plane-strain compliance while all three are >= 0.
DrivingForce drivingForcePlaneStrain(const Voigt& effectiveStress, double youngsModulus, double nu);
inline double drivingForcePlaneStrainValue(const Voigt& s, double youngsModulus, double nu) {
  const double mean = 0.5 * (s[0] + s[1]);
  const double halfDiff = 0.5 * (s[0] - s[1]);
  const double radius = std::sqrt(halfDiff * halfDiff + s[2] * s[2]);
  return drivingForceOfPrincipal(mean + radius, mean - radius, nu * (s[0] + s[1]), youngsModulus, nu);
}

// d sigma_nn / d sigma_voigt for sigma_nn = n . sigma n: [n_x^2, n_y^2, 2 n_x n_y].
inline Voigt normalProjector(const Vec2& n) { return {n[0] * n[0], n[1] * n[1], 2.0 * n[0] * n[1]}; }

}  // namespace ecm
