#include "calibration/fracture_energy.hpp"

#include <cmath>
#include <sstream>

#include "calibration/calibration_error.hpp"
#include "material/parameter_check.hpp"
#include "material/smeared_crack.hpp"

namespace ecm::calibration {

double fractureEnergy(const DamageLawParams& law, double bandWidth) {
  requireInRange("band_width h (mm)", bandWidth, 0.0, 1e300);
  return bandWidth * dissipationToFailure(law);  // G_F = h int_0^1 F(D) dD, F of Eq. (13)
}

double minimumFractureEnergy(double e, double ft, double h) { return h * ft * ft / (2.0 * e); }

SofteningModulusSolution solveSofteningModulus(const DamageLawParams& shape, double gf, double width) {
  DamageLawParams law = shape;
  law.softeningModulus = 1.0;  // placeholder so that the other parameters can be range-checked
  try {
    law.validate();
    requireInRange("fracture_energy GF (N/mm)", gf, 0.0, 1e300);
    requireInRange("width (mm)", width, 0.0, 1e300);
  } catch (const ParameterError& e) {
    throw CalibrationError(e.what());
  }
  const double least = minimumFractureEnergy(shape.youngsModulus, shape.tensileStrength, width);
  if (!(gf > least)) {
    std::ostringstream msg;
    msg.precision(10);
    msg << "fracture_energy G_F = " << gf << " N/mm is not above the elastic minimum h ft^2/(2E) = " << least
        << " N/mm (h = " << width << " mm, ft = " << shape.tensileStrength << " MPa, E = " << shape.youngsModulus
        << " MPa): no softening law of the form of Eq. (13) dissipates so little";
    throw CalibrationError(msg.str());
  }
  SofteningModulusSolution s;
  try {
    s.softeningModulus = regularisedSofteningModulus(law, gf, width);
  } catch (const RegularisationError& e) {
    throw CalibrationError(e.what());
  }
  law.softeningModulus = s.softeningModulus;
  s.fractureEnergy = fractureEnergy(law, width);
  s.relativeError = (s.fractureEnergy - gf) / gf;
  return s;
}

}  // namespace ecm::calibration
