// The secant response of a cracked band and the unloading update that takes it
// (material/secant_response.hpp, docs/model.md "The secant response of an unloading band").
#include <algorithm>

#include "material/two_phase_point.hpp"

namespace ecm {

SecantResponse TwoPhasePoint::secantResponse(const BandState& b) const {
  SecantResponse r;
  r.crackNormal = b.crackNormal;
  r.onsetStrain = b.onsetStrain;
  r.volumeFraction = b.volumeFraction;
  r.integrity = b.integrity;
  const JumpMap N = jumpToStrain(b.crackNormal);
  const double f = b.volumeFraction, x0 = b.integrity;
  const Tangent& a = stiffness();
  // Eq. (6) with a_L = x0 a: N^T a eps / (1 - f) = (f / (1 - f) + x0) N^T a (eps_on + N [u] / h),
  // that is K [u] = N^T a eps / (1 - f) - (f / (1 - f) + x0) N^T a eps_on with the secant K of Eq. (9).
  const Mat2 kInverse = secantJacobian(b, x0).inverse();
  const Eigen::Matrix<double, 2, 3> nTa = N.transpose() * a;
  r.jumpOfStrain = kInverse * nTa / (1.0 - f);
  r.jumpAtZeroStrain = -(f / (1.0 - f) + x0) * (kInverse * (nTa * b.onsetStrain));
  // a eps_L = a (eps_on + N [u] / h), Eq. (3).
  r.bandStressOfStrain = a * N * r.jumpOfStrain / bandWidth_;
  r.bandStressAtZeroStrain = a * (b.onsetStrain + N * r.jumpAtZeroStrain / bandWidth_);
  // The loading surface F(x0) >= F(1) of Eq. (12): the predictor's test, without its pow per update.
  r.threshold = std::max(law_.onsetDrivingForce(), law_.loadingSurface(x0).threshold);
  return r;
}

UpdateResult TwoPhasePoint::updateCracked(BandState& b, SecantResponse& secant, Voigt& strain, const Voigt& increment,
                                         UpdateOptions options) const {
  if (options.tangent) return updateCracked(b, strain, increment, options);
  // Built whenever it is not the band's (not only after an unloading increment): which path an
  // update takes then depends on the band state alone, so a restarted run, whose responses start
  // empty, takes the same paths as an uninterrupted one, bit for bit.
  if (!secant.builtFor(b)) secant = secantResponse(b);
  const Voigt eps = strain + increment;
  const Voigt aBand = secant.bandStressOfStrain * eps + secant.bandStressAtZeroStrain;  // a eps_L
  // Y of Eq. (12) above the loading surface (or not a number): the band loads, the full update.
  if (!(law_.drivingForceValue(aBand) <= secant.threshold)) return updateCracked(b, strain, increment, options);
  const double f = b.volumeFraction;
  const Voigt aEps = stiffness() * eps;
  UpdateResult res;
  res.stress = (aEps - f * aBand) / (1.0 - f);                                                    // Eqs. (2), (4)
  res.residual = (jumpToStrain(b.crackNormal).transpose() * (res.stress - b.integrity * aBand)).norm();  // Eq. (6)
  // The maps hold Eq. (6) to round-off; should they not here, the predictor's solve decides.
  if (!(res.residual <= crackedTolerance(aEps, f))) return updateCracked(b, strain, increment, options);
  b.jump = secant.jumpOfStrain * eps + secant.jumpAtZeroStrain;
  strain = eps;
  return res;
}

}  // namespace ecm
