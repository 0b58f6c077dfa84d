#pragma once
// Hordijk's traction-opening curve (Cornelissen, Hordijk and Reinhardt 1986) as a cohesive
// interface:
//   T(w) = f_t [(1 + (c1 w/wc)^3) exp(-c2 w/wc) - (w/wc)(1 + c1^3) exp(-c2)],  T = 0 for w >= wc,
//   c1 = 3, c2 = 6.93, wc = 5.14 G_F / f_t,
// behind an elastic stiffness K0: t = K0 delta up to f_t; on the loading envelope the jump is
// delta = w + T(w)/K0 (w the crack opening). Irreversible: the largest opening reached, w_max,
// is the state; below its jump the interface unloads along the secant to the origin. A jump in
// compression gets the full stiffness K0 (contact) and changes nothing.
#include "cohesive/band_interface.hpp"  // InterfaceResponse

namespace ecm::cohesive {

struct HordijkInterface {
  double tensileStrength = 0.0;   // f_t' (MPa)
  double fractureEnergy = 0.0;    // G_F (N/mm)
  double initialStiffness = 0.0;  // K0 (MPa/mm)
  static constexpr double c1 = 3.0, c2 = 6.93;
  double criticalOpening() const { return 5.14 * fractureEnergy / tensileStrength; }  // wc
  // Throws ParameterError, also when K0 does not exceed the curve's steepest slope (then the
  // envelope delta(w) is not monotonic: the interface itself would snap back).
  void validate() const;
};

struct HordijkState {
  double maxOpening = 0.0;  // w_max (mm), 0 until the traction has reached f_t
  bool cracked = false;     // the envelope's softening branch has been reached
};

double hordijkTraction(const HordijkInterface& p, double opening);  // T(w)
double hordijkSlope(const HordijkInterface& p, double opening);     // dT/dw
// int_0^w T dw' in closed form; at w >= wc the whole area, which is G_F times
// hordijkAreaFactor() = 1.000768 (5.14 is the rounded inverse of the normalised curve's area on
// [0, 1]; the curve reaches zero at wc and is cut there).
double hordijkArea(const HordijkInterface& p, double opening);
double hordijkAreaFactor();

InterfaceResponse updateHordijk(const HordijkInterface& p, HordijkState& state, double jump);

}  // namespace ecm::cohesive
