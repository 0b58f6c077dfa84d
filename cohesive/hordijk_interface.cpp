#include "cohesive/hordijk_interface.hpp"

#include <cmath>
#include <string>

#include "material/parameter_check.hpp"

namespace ecm::cohesive {

namespace {

constexpr double c1 = HordijkInterface::c1, c2 = HordijkInterface::c2;

// int_0^z (1 + c1^3 s^3) exp(-c2 s) ds - (1 + c1^3) exp(-c2) z^2 / 2 (z = w / wc).
double areaPerWc(double z) {
  const double a = c2, e = std::exp(-a * z);
  const double constant = (1.0 - e) / a;
  const double cubic = 6.0 / (a * a * a * a) - e * (z * z * z / a + 3.0 * z * z / (a * a) + 6.0 * z / (a * a * a) + 6.0 / (a * a * a * a));
  return constant + c1 * c1 * c1 * cubic - (1.0 + c1 * c1 * c1) * std::exp(-c2) * 0.5 * z * z;
}

// The jump on the envelope at opening w: delta = w + T(w)/K0.
double envelopeJump(const HordijkInterface& p, double w) { return w + hordijkTraction(p, w) / p.initialStiffness; }

}  // namespace

void HordijkInterface::validate() const {
  requireInRange("tensile strength f_t'", tensileStrength, 0.0, INFINITY);
  requireInRange("fracture energy G_F", fractureEnergy, 0.0, INFINITY);
  requireInRange("initial stiffness K0", initialStiffness, 0.0, INFINITY);
  const double steepest = -hordijkSlope(*this, 0.0);  // T' is steepest at w = 0
  if (!(initialStiffness > steepest))
    throw ParameterError("initial stiffness K0 = " + std::to_string(initialStiffness) +
                         " MPa/mm must exceed the curve's steepest softening slope " + std::to_string(steepest) + " MPa/mm");
}

double hordijkTraction(const HordijkInterface& p, double w) {
  const double wc = p.criticalOpening(), z = w / wc;
  if (z >= 1.0) return 0.0;
  return p.tensileStrength * ((1.0 + std::pow(c1 * z, 3)) * std::exp(-c2 * z) - z * (1.0 + c1 * c1 * c1) * std::exp(-c2));
}

double hordijkSlope(const HordijkInterface& p, double w) {
  const double wc = p.criticalOpening(), z = w / wc;
  if (z >= 1.0) return 0.0;
  const double dz = (3.0 * c1 * c1 * c1 * z * z - c2 * (1.0 + std::pow(c1 * z, 3))) * std::exp(-c2 * z) - (1.0 + c1 * c1 * c1) * std::exp(-c2);
  return p.tensileStrength * dz / wc;
}

double hordijkArea(const HordijkInterface& p, double w) {
  const double wc = p.criticalOpening();
  return p.tensileStrength * wc * areaPerWc(std::min(w / wc, 1.0));
}

double hordijkAreaFactor() { return 5.14 * areaPerWc(1.0); }

InterfaceResponse updateHordijk(const HordijkInterface& p, HordijkState& state, double jump) {
  const double k0 = p.initialStiffness, ft = p.tensileStrength, wc = p.criticalOpening();
  InterfaceResponse r;
  if (jump <= 0.0) {  // contact: full stiffness, no damage
    r.traction = k0 * jump;
    r.tangent = k0;
    r.stored = 0.5 * k0 * jump * jump;
    return r;
  }
  const double wOld = state.maxOpening;
  const double jumpOld = state.cracked ? (wOld >= wc ? INFINITY : envelopeJump(p, wOld)) : ft / k0;
  if (jump > jumpOld && wOld < wc) {
    // Loading on the softening envelope: solve w + T(w)/K0 = delta for w in [wOld, delta]
    // (g(w) = w + T/K0 - delta increases: K0 exceeds the steepest slope). Newton, bisection-safe.
    double lo = wOld, hi = jump, w = std::min(std::max(wOld, jump - ft / k0), jump);
    if (envelopeJump(p, wc) <= jump) {
      w = wc;
    } else {
      for (int it = 0; it < 100; ++it) {
        const double g = envelopeJump(p, w) - jump;
        if (g > 0.0) hi = w; else lo = w;
        double next = w - g / (1.0 + hordijkSlope(p, w) / k0);
        if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
        if (std::abs(next - w) <= 1e-15 * (wc + w)) { w = next; break; }
        w = next;
      }
    }
    const double t = hordijkTraction(p, w);
    state.maxOpening = w;
    state.cracked = true;
    const double slope = hordijkSlope(p, w);
    r.traction = t;
    r.tangent = w >= wc ? 0.0 : slope / (1.0 + slope / k0);  // dT/dw dw/ddelta
    // Dissipated to w: int_0^w T dw - T w / 2 (the work along the envelope minus the stored
    // T delta / 2; docs/cohesive.md).
    const double dissipatedOld = hordijkArea(p, wOld) - 0.5 * hordijkTraction(p, wOld) * wOld;
    r.dissipation = hordijkArea(p, w) - 0.5 * t * w - dissipatedOld;
    r.stored = 0.5 * t * jump;
    return r;
  }
  // Below the envelope (or not yet at f_t): the secant to the origin.
  const double secant = !state.cracked ? k0 : (wOld >= wc ? 0.0 : hordijkTraction(p, wOld) / jumpOld);
  r.traction = secant * jump;
  r.tangent = secant;
  r.stored = 0.5 * secant * jump * jump;
  return r;
}

}  // namespace ecm::cohesive
