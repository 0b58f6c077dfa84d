#pragma once
// The damage driving force of Eq. (12) in 3D: Y = 1/2 sigma+ : a^-1 : sigma+ over the three
// principal values of the effective stress (docs/model.md, "The point in 3D").
#include "material/driving_force.hpp"
#include "material/voigt3.hpp"

namespace ecm {

struct DrivingForce3 {
  double value = 0.0;                     // Y (MPa)
  Voigt6 stressGradient = Voigt6::Zero(); // dY/d sigma as a Voigt row: dY = g . d(sigma_voigt)
};

// Y and its gradient sum_i dY/dp_i (n_i (x) n_i) for the isotropic compliance of (E, nu). A
// principal value zero to round-off counts as opening (as in 2D, material/driving_force.cpp).
// Where all three principal values have one sign (the invariants tell, no eigen-decomposition)
// Y is the closed form sigma : a^-1 : sigma / 2, or 0.
DrivingForce3 drivingForce3(const Voigt6& effectiveStress, double youngsModulus, double nu);
// Y alone.
double drivingForceValue3(const Voigt6& effectiveStress, double youngsModulus, double nu);


// The largest principal value of a Voigt stress and its unit direction.
struct Principal3 {
  double first;
  Vec3 firstDirection;
};
Principal3 largestPrincipal(const Voigt6& s);

}  // namespace ecm
