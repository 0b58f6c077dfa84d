#include "material/two_phase_point.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <vector>

#include "material/cracked_point_update.hpp"
#include "material/jump_stability.hpp"
#include "material/driving_force.hpp"
#include "material/parameter_check.hpp"

namespace ecm {

template class CrackedPoint<PlaneBand, TwoPhasePoint>;  // material/cracked_point_update.hpp

std::string effectiveSizeProblem(double effectiveSize, double bandWidth, int bands) {
  if (effectiveSize >= minimumEffectiveSize(bandWidth, bands)) return "";
  std::ostringstream msg;
  msg.precision(10);
  msg << "H = " << effectiveSize << " mm is below the smallest effective size " << (bands > 1 ? "2 h" : "h") << " (1 + "
      << kMinimumSizeMargin << ") = " << minimumEffectiveSize(bandWidth, bands) << " mm for the band width h = "
      << bandWidth << " mm: a bulk thinner than that (1 - "
      << (bands > 1 ? "f1 - f2" : "f") << " < 1e-6, Eq. (1)) leaves its stress to round-off";
  if (bands > 1) msg << " (second_band: orthogonal needs room for two bands)";
  msg << " (docs/model.md)";
  return msg.str();
}

const char* toString(SecondBandOption o) { return o == SecondBandOption::Orthogonal ? "orthogonal" : "off"; }

void EnrichedParams::validate() const {
  band.validate();
  requireInRange("band_width h (mm)", bandWidth, 0.0, 1e300);
}

TwoPhasePoint::TwoPhasePoint(const EnrichedParams& p)
    : law_((p.validate(), p.band)),
      bandWidth_(p.bandWidth),
      onsetBound_(law_.drivingForceBound()),
      shearModulus_(law_.stiffness()(2, 2)),
      acousticRatio_((law_.stiffness()(0, 1) + law_.stiffness()(2, 2)) / law_.stiffness()(0, 0)),
      secondBand_(p.secondBand),
      secondOnsetStress_(std::sqrt(2.0 * law_.onsetDrivingForce() / law_.compliance()(0, 0))) {}

double TwoPhasePoint::intactDrivingForce(const Voigt& strain) const {
  return law_.drivingForceValue(stiffness() * strain);  // bitwise drivingForce().value
}

std::optional<double> TwoPhasePoint::onsetFraction(const Voigt& strain, const Voigt& increment) const {
  return law_.onsetFraction(strain, increment);
}

double TwoPhasePoint::stressControlledMargin(const Tangent& d, unsigned stressControlled) const {
  int idx[3], m = 0;
  for (int i = 0; i < 3; ++i)
    if (stressControlled & (1u << i)) idx[m++] = i;
  double dMargin = 0.0;
  if (m == 1) {
    dMargin = d(idx[0], idx[0]);
  } else if (m == 2) {
    Mat2 block;
    block << d(idx[0], idx[0]), d(idx[0], idx[1]), d(idx[1], idx[0]), d(idx[1], idx[1]);
    dMargin = smallestRealEigenvalue(block);
  } else {
    dMargin = d.eigenvalues().real().minCoeff();
  }
  return dMargin / law_.law().youngsModulus;
}

UpdateResult TwoPhasePoint::updateIntactSlow(Voigt& strain, const Voigt& increment, const EffectiveSize& size,
                                            std::optional<BandState>& onset, UpdateOptions options,
                                            std::optional<BandState>* secondOnset) const {
  UpdateResult r;
  r.stress = stiffness() * (strain + increment);
  r.tangent = stiffness();
  const std::optional<double> alpha = onsetFraction(strain, increment);
  if (!alpha) {
    strain += increment;
    return r;
  }
  const Voigt onsetStrain = strain + *alpha * increment;
  const Vec2 normal = options.onsetNormal ? canonicalNormal(*options.onsetNormal)
                                          : canonicalNormal(principalStresses(stiffness() * onsetStrain).firstDirection);
  std::optional<BandState> b = bandAtOnset(onsetStrain, normal, size(normal), r);
  if (!b) return r;
  Voigt cracked = onsetStrain;
  r = secondOnset ? updateCracked(*b, nullptr, cracked, (1.0 - *alpha) * increment, size, *secondOnset, options)
                  : updateCracked(*b, cracked, (1.0 - *alpha) * increment, options);
  if (r.converged()) {
    strain = cracked;
    onset = b;
  }
  return r;
}

UpdateResult TwoPhasePoint::update(EnrichedState& state, const Voigt& increment, const EffectiveSize& size,
                                   UpdateOptions options) const {
  if (!opensSecondBand()) {
    if (state.band) return updateCracked(*state.band, state.strain, increment, options);
    return updateIntact(state.strain, increment, size, state.band, options);
  }
  if (state.band) {
    std::optional<BandState> second;
    const UpdateResult r = updateCracked(*state.band, state.secondBand ? &*state.secondBand : nullptr, state.strain,
                                         increment, size, second, options);
    if (second) state.secondBand = second;
    return r;
  }
  return updateIntact(state.strain, increment, size, state.band, state.secondBand, options);
}

}  // namespace ecm
