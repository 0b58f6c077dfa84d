#pragma once
// ecm's band law (Eqs. (11)-(13)) as a 1D cohesive interface of thickness h (bandWidth): the
// jump delta = h eps_L, the driving force Y = E eps_L^2 / 2 for eps_L > 0 (0 in compression),
// the integrity x = 1 - D from F(x) = Y (irreversible), the traction t = x E eps_L. A closing
// crack gets no stiffness back (as in ecm: the spectral split acts on Y only).
// Pure functions over a plain state; the scalar functions of F come from material/.
#include <stdexcept>

#include "material/damage_function.hpp"

namespace ecm::cohesive {

struct BandInterface {
  DamageLawParams law;     // E, f_t', E_p, n of the band
  double bandWidth = 0.0;  // h (mm)
  void validate() const;   // throws ParameterError
};

struct BandState {
  double integrity = 1.0;  // x = 1 - D
};

// The response at a jump, from the state at the start of the increment.
struct InterfaceResponse {
  double traction = 0.0;     // t (MPa)
  double tangent = 0.0;      // dt / d delta (MPa/mm), consistent
  double dissipation = 0.0;  // energy dissipated per area in the increment (N/mm)
  double stored = 0.0;       // energy stored per area at the end of it (N/mm)
};

// A jump a law cannot answer (an opening past the end of a table): the solver treats it as a
// failed Newton iteration, so a trial iterate that overshoots costs a smaller step, and a run
// whose converged jumps need it ends with this message.
struct InterfaceLawError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// `state` is updated to the end of the increment.
InterfaceResponse updateBand(const BandInterface& p, BandState& state, double jump);

// Work per area to complete failure: h int_0^1 F dD, which is G_F (docs/model.md, identities).
double bandFractureEnergy(const BandInterface& p);

}  // namespace ecm::cohesive
