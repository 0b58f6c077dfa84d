#pragma once
// The closed-form part of the stress phase, shared by the fused grid-to-particle transfer (USL)
// and Solver::updateStresses: an elastic point, or an enriched point that stays intact far from
// onset (TwoPhasePoint::surelyIntact). Anything else (a cracked point, a point near onset, a
// smeared crack, a non-finite stress) returns false, changes nothing, and takes the full update.
#include <cstdint>

#include "mpm/solver.hpp"

namespace ecm::mpm {

inline bool closedFormStress(const MaterialKernel& k, const Voigt& increment, std::int32_t band, Voigt& strain,
                             Voigt& stress) {
  if (k.kind == ModelKind::SmearedCrack || (k.kind == ModelKind::Enriched && band >= 0)) return false;
  const Voigt end = strain + increment;
  const Voigt s = k.stiffness * end;  // Eq. (4) with no band
  if (!s.allFinite() || (k.kind == ModelKind::Enriched && !k.enriched->surelyIntact(s))) return false;
  strain = end;
  stress = s;
  return true;
}

}  // namespace ecm::mpm
