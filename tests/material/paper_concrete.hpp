#pragma once
// The paper's DEN concrete (Nguyen, numerical examples; G_F = 0.11 N/mm per the verified
// erratum): E = 32000 MPa, nu = 0.2, f_t' = 3.0 MPa, E_p = 8.184 MPa, n = 0.128, h = 0.05 mm.
#include "material/material.hpp"

namespace ecm::test {

inline constexpr double kE = 32000.0, kNu = 0.2, kFt = 3.0, kEp = 8.184, kN = 0.128, kH = 0.05, kGF = 0.11;
// Snap-back size h (E + E_p) / E_p (docs/model.md, identities): 195.55 mm.
inline constexpr double kSnapBackSize = kH * (kE + kEp) / kEp;

inline BandDamageParams paperBand(double nu = kNu, Hypothesis hyp = Hypothesis::PlaneStress) {
  return {{kE, nu, hyp}, kFt, kEp, kN};
}
inline EnrichedParams paperEnriched(double nu = kNu, Hypothesis hyp = Hypothesis::PlaneStress) {
  return {paperBand(nu, hyp), kH};
}

}  // namespace ecm::test
