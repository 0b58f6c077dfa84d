#pragma once
// The band's fracture energy and its inverse: G_F = h int_0^1 F(D) dD with F of Eq. (13),
// and the softening modulus E_p that makes a band of width h dissipate a given G_F.
#include "material/damage_function.hpp"

namespace ecm::calibration {

// Forward: G_F = h * dissipationToFailure(law) (N/mm).
double fractureEnergy(const DamageLawParams& law, double bandWidth);

// The least energy any law of the form of Eq. (13) dissipates in a band of width h:
// h f_t'^2 / (2E), the elastic energy at peak, approached as E_p -> infinity.
double minimumFractureEnergy(double youngsModulus, double tensileStrength, double bandWidth);

struct SofteningModulusSolution {
  double softeningModulus = 0.0;  // E_p (MPa)
  double fractureEnergy = 0.0;    // h int F dD at that E_p (N/mm)
  double relativeError = 0.0;     // (that - target) / target
};

// E_p for the given E, f_t', n (shape.softeningModulus is ignored) such that a band of width
// `width` dissipates `fractureEnergy`: Brent on log E_p (regularisedSofteningModulus of the
// material library, the same root for h as for a crack-band element size H).
// Throws CalibrationError for G_F <= minimumFractureEnergy and for out-of-range inputs.
SofteningModulusSolution solveSofteningModulus(const DamageLawParams& shape, double fractureEnergy, double width);

}  // namespace ecm::calibration
