#pragma once
// Parameters from Nguyen's enriched-MPM paper used by the calibration tests.
#include "../material/paper_concrete.hpp"  // the DEN concrete: kE, kFt, kGF, kH, kN, kEp
#include "material/damage_function.hpp"

namespace ecm::test {

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
