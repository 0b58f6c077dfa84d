#include "material/two_phase_point_3d.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <Eigen/Eigenvalues>

#include "material/band_onset.hpp"
#include "material/cracked_point_update.hpp"
#include "material/jump_stability.hpp"
#include "material/parameter_check.hpp"

namespace ecm {

template class CrackedPoint<SpaceBand, TwoPhasePoint3D>;  // material/cracked_point_update.hpp

namespace {

Voigt6 aTimes(const Tangent6& a, const Voigt6& e) { return a * e; }

}  // namespace

TwoPhasePoint3D::TwoPhasePoint3D(const EnrichedParams& p)
    : law_((p.validate(), p.band)),
      e_(p.band.elastic.youngsModulus),
      nu_(p.band.elastic.poissonRatio),
      bandWidth_(p.bandWidth),
      stiffness_(isotropicStiffness3(e_, nu_)),
      onsetBound_(0.5 * std::max(1.0 + nu_, 1.0 - 2.0 * nu_) / e_),
      shearModulus_(stiffness_(3, 3)),
      acousticRatio_((stiffness_(0, 1) + stiffness_(3, 3)) / stiffness_(0, 0)) {
  if (p.secondBand != SecondBandOption::Off)
    throw ParameterError(std::string("second_band: ") + toString(p.secondBand) +
                         " is not offered in 3D: a second band needs a normal chosen among the directions of the "
                         "first band's plane, which the 2D rule (the band's tangent) does not fix (docs/model.md)", "second_band");
}

BandResponse3 TwoPhasePoint3D::evaluateBand(const BandDamageLaw::LoadingSurface& surface, const Voigt6& strain,
                                            bool loadingTangent) const {
  BandResponse3 r;
  const Voigt6 effective = stiffness_ * strain;
  const DrivingForce3 y = drivingForce3(effective, e_, nu_);  // Eq. (12)
  r.drivingForce = y.value;
  const BandDamageLaw::IntegrityResponse x = law_.integrityFor(surface, y.value, loadingTangent);  // Eq. (13)
  r.loading = x.loading;
  r.integrity = x.integrity;
  r.stress = r.integrity * effective;  // Eq. (11)
  if (x.loadingTangent) {  // dx/deps = (dx/dY) (dY/dsigma) a
    const Eigen::Matrix<double, 1, 6> dxde = x.dxdy * (y.stressGradient.transpose() * stiffness_);
    r.tangent = r.integrity * stiffness_ + effective * dxde;
  } else {
    r.tangent = r.integrity * stiffness_;
  }
  return r;
}

Voigt6 TwoPhasePoint3D::stress(const BandState3& b, const Voigt6& strain) const {
  return equilibrium(b, law_.loadingSurface(b.integrity), strain, b.jump, false).stress;
}

double TwoPhasePoint3D::storedEnergy(const BandState3& b, const Voigt6& strain) const {
  const BandEquilibrium3 eq = equilibrium(b, law_.loadingSurface(b.integrity), strain, b.jump, false);
  const double f = b.volumeFraction;
  const Voigt6 bulkStrain = (strain - f * eq.bandStrain) / (1.0 - f);  // Eq. (2)
  return 0.5 * ((1.0 - f) * eq.stress.dot(bulkStrain) + f * eq.band.stress.dot(eq.bandStrain));
}

std::optional<double> TwoPhasePoint3D::onsetFraction(const Voigt6& strain, const Voigt6& increment) const {
  const double yOnset = law_.onsetDrivingForce();
  return onsetFractionOf([&](double a) { return drivingForceValue3(aTimes(stiffness_, strain + a * increment), e_, nu_) - yOnset; },
                         yOnset);
}

Vec3 TwoPhasePoint3D::onsetNormal(const Voigt6& strain) const {
  return canonicalNormal3(largestPrincipal(stiffness_ * strain).firstDirection);
}

UpdateResult3 TwoPhasePoint3D::updateIntactSlow(Voigt6& strain, const Voigt6& increment, const EffectiveSize3& size,
                                                std::optional<BandState3>& onset, UpdateOptions options) const {
  UpdateResult3 r;
  r.stress = stiffness_ * (strain + increment);
  r.tangent = stiffness_;
  const std::optional<double> alpha = onsetFraction(strain, increment);
  if (!alpha) {
    strain += increment;
    return r;
  }
  const Voigt6 onsetStrain = strain + *alpha * increment;
  const Vec3 normal = onsetNormal(onsetStrain);
  std::optional<BandState3> b = bandAtOnset(onsetStrain, normal, size(normal), r);
  if (!b) return r;
  Voigt6 cracked = onsetStrain;
  r = updateCracked(*b, cracked, (1.0 - *alpha) * increment, options);
  if (r.converged()) {
    strain = cracked;
    onset = b;
  }
  return r;
}

double TwoPhasePoint3D::stressControlledMargin(const Tangent6& d, unsigned stressControlled) const {
  std::vector<int> idx;
  for (int i = 0; i < 6; ++i)
    if (stressControlled & (1u << i)) idx.push_back(i);
  const int m = static_cast<int>(idx.size());
  Eigen::MatrixXd block(m, m);
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j) block(i, j) = d(idx[i], idx[j]);
  const double margin = m == 1 ? block(0, 0) : smallestRealEigenvalue(block);
  return margin / e_;
}

}  // namespace ecm
