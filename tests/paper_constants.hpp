#pragma once
// The paper's constants, defined once for every test (units: mm, N, MPa).
// The DEN concrete (Nguyen, numerical examples; G_F = 0.11 N/mm per the verified erratum):
// E = 32000 MPa, nu = 0.2, f_t' = 3.0 MPa, E_p = 8.184 MPa, n = 0.128, h = 0.05 mm.
#include "material/damage_function.hpp"
#include "material/material.hpp"

namespace ecm::test {

inline constexpr double kE = 32000.0, kNu = 0.2, kFt = 3.0, kEp = 8.184, kN = 0.128, kBandWidth = 0.05, kGF = 0.11;
// Snap-back size h (E + E_p) / E_p (docs/model.md, identities): 195.55 mm.
inline constexpr double kSnapBackSize = kBandWidth * (kE + kEp) / kEp;

inline BandDamageParams paperBand(double nu = kNu, Hypothesis hyp = Hypothesis::PlaneStress) {
  return {{kE, nu, hyp}, kFt, kEp, kN};
}
inline EnrichedParams paperEnriched(double nu = kNu, Hypothesis hyp = Hypothesis::PlaneStress) {
  return {paperBand(nu, hyp), kBandWidth};
}

inline DamageLawParams concreteShape(double n = kN) { return {kE, kFt, 0.0, n}; }

// The DEN concrete as an enriched material (plane stress), as the scenes declare it.
inline MaterialParams paperConcreteMaterial() {
  MaterialParams p{.name = "paper-concrete",
                   .model = ModelKind::Enriched, .elastic = {kE, kNu, Hypothesis::PlaneStress},
                   .tensileStrength = kFt, .softeningModulus = kEp, .softeningExponent = kN, .bandWidth = kBandWidth};
  return p;
}

// The three phases of the mesoscale RVE, Table 1 (h = 0.005 mm, n = 0.179).
struct RvePhase {
  const char* name;
  double youngsModulus, tensileStrength, softeningModulus;
};
inline constexpr double kRveBandWidth = 0.005, kRveExponent = 0.179;
inline constexpr RvePhase kRvePhases[] = {
    {"inclusion", 45000.0, 3.0, 10.0}, {"matrix", 30000.0, 2.0, 10.0}, {"itz", 30000.0, 1.5, 20.0}};

}  // namespace ecm::test
