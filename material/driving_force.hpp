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

// `compliance` is the (isotropic) in-plane a^-1; for plane strain sigma_zz is not split
// (docs/model.md). Because Y is a symmetric function of the principal stresses, its gradient is
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

// d sigma_nn / d sigma_voigt for sigma_nn = n . sigma n: [n_x^2, n_y^2, 2 n_x n_y].
inline Voigt normalProjector(const Vec2& n) { return {n[0] * n[0], n[1] * n[1], 2.0 * n[0] * n[1]}; }

}  // namespace ecm
