#pragma once
// Parameters from Nguyen's enriched-MPM paper used by the calibration tests.
#include "material/damage_function.hpp"

namespace ecm::test {

// DEN concrete (G_F = 0.11 N/mm per the verified erratum; E_p = 8.184 MPa, n = 0.128, h = 0.05 mm).
inline constexpr double kE = 32000.0, kFt = 3.0, kGF = 0.11, kH = 0.05, kN = 0.128, kEp = 8.184;

inline DamageLawParams concreteShape(double n = kN) { return {kE, kFt, 0.0, n}; }

// The three phases of the mesoscale RVE, Table 1 (h = 0.005 mm, n = 0.179).
struct RvePhase {
  const char* name;
  double youngsModulus, tensileStrength, softeningModulus;
};
inline constexpr double kRveBandWidth = 0.005, kRveExponent = 0.179;
inline constexpr RvePhase kRvePhases[] = {
    {"inclusion", 45000.0, 3.0, 10.0}, {"matrix", 30000.0, 2.0, 10.0}, {"itz", 30000.0, 1.5, 20.0}};

}  // namespace ecm::test
