#include "cohesive/band_interface.hpp"

#include "material/parameter_check.hpp"

namespace ecm::cohesive {

void BandInterface::validate() const {
  law.validate();
  if (!(bandWidth > 0.0)) throw ParameterError("band width h must be > 0");
}

InterfaceResponse updateBand(const BandInterface& p, BandState& state, double jump) {
  const double e = p.law.youngsModulus, h = p.bandWidth;
  const double strain = jump / h;                                   // eps_L = delta / h
  const double y = strain > 0.0 ? 0.5 * e * strain * strain : 0.0;  // Eq. (12), tension only
  const double xOld = state.integrity;
  InterfaceResponse r;
  double dxdy = 0.0;
  if (y > damageFunction(p.law, xOld)) {  // loading: F(x) = Y, Eq. (13)
    const double x = solveIntegrity(p.law, y, xOld);
    dxdy = 1.0 / damageFunctionSlope(p.law, x);
    r.dissipation = h * dissipationBetween(p.law, xOld, x);
    state.integrity = x;
  }
  const double x = state.integrity;
  r.traction = x * e * strain;                                 // Eq. (11) in 1D
  r.tangent = e / h * (x + strain * dxdy * e * strain);        // d(x E eps)/d eps with dx = dx/dY E eps d eps
  r.stored = h * 0.5 * x * e * strain * strain;
  return r;
}

double bandFractureEnergy(const BandInterface& p) { return p.bandWidth * dissipationToFailure(p.law); }

}  // namespace ecm::cohesive
