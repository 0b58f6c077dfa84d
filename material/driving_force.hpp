#pragma once
// The damage driving force of Eq. (12): Y = 1/2 sigma+ : a^-1 : sigma+ of the effective stress
// sigma = a : eps, with sigma+ its positive part from the eigen-decomposition.
#include "material/voigt.hpp"

namespace ecm {

struct DrivingForce {
  double value = 0.0;                   // Y (MPa)
  Voigt stressGradient = Voigt::Zero(); // dY/d sigma as a Voigt row: dY = g . d(sigma_voigt)
};

// `compliance` is the (isotropic) in-plane a^-1; for plane strain sigma_zz is not split
// (MODEL-NOTES). Because Y is a symmetric function of the principal stresses, its gradient is
// sum_i dY/dp_i (n_i (x) n_i), well defined also at repeated principal stresses.
DrivingForce drivingForce(const Voigt& effectiveStress, const Tangent& compliance);

}  // namespace ecm
