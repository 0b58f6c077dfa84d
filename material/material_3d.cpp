#include "material/material_3d.hpp"

#include <sstream>

namespace ecm {

namespace {
MaterialParams checked3D(const MaterialParams& p) {
  if (p.elastic.hypothesis != Hypothesis::ThreeDimensional)
    throw ParameterError("a 3D material needs hypothesis: three_dimensional (the material has " +
                         std::string(toString(p.elastic.hypothesis)) + ")", "hypothesis");
  if (p.model == ModelKind::SmearedCrack)
    throw ParameterError("model smeared_crack is not offered in 3D: use enriched or linear_elastic", "model");
  p.validate();
  return p;
}
}  // namespace

Material3D::Material3D(const MaterialParams& p)
    : params_(checked3D(p)),
      stiffness_(isotropicStiffness3(p.elastic.youngsModulus, p.elastic.poissonRatio)) {
  if (params_.model == ModelKind::Enriched) enriched_.emplace(params_.enriched());
}

UpdateResult3 Material3D::updateOnce(MaterialPoint3& point, const Voigt6& d, const EffectiveSize3& size,
                                     const UpdateOptions& options) const {
  if (!enriched_) {
    point.strain += d;
    UpdateResult3 r;
    r.stress = stiffness_ * point.strain;
    r.tangent = stiffness_;
    return r;
  }
  if (point.band) return enriched_->updateCracked(*point.band, point.strain, d, options);
  return enriched_->updateIntact(point.strain, d, size, point.band, options);
}

UpdateResult3 Material3D::update(MaterialPoint3& point, const Voigt6& d, const EffectiveSize3& size,
                                 const UpdateOptions& options) const {
  UpdateResult3 r = updateOnce(point, d, size, options);
  if (r.status != UpdateStatus::NotConverged || options.substepLevels <= 0) return r;
  for (int level = 1; level <= options.substepLevels; ++level) {
    const int n = 1 << level;
    MaterialPoint3 trial = point;
    double dissipation = 0.0;
    bool ok = true, released = false;
    for (int i = 0; i < n && ok; ++i) {
      r = updateOnce(trial, d / n, size, options);
      ok = r.converged();
      dissipation += r.dissipation;
      released = released || r.released;
    }
    r.substeps = n;
    if (!ok) continue;
    point = trial;
    r.dissipation = dissipation;
    r.released = released;
    return r;
  }
  return r;
}

Voigt6 Material3D::stress(const MaterialPoint3& point) const {
  if (enriched_ && point.band) return enriched_->stress(*point.band, point.strain);
  return stiffness_ * point.strain;
}

double Material3D::storedEnergy(const MaterialPoint3& point) const {
  if (enriched_ && point.band) return enriched_->storedEnergy(*point.band, point.strain);
  return 0.5 * point.strain.dot(stiffness_ * point.strain);
}

std::string Material3D::explain(const UpdateResult3& r) const {
  std::ostringstream msg;
  msg.precision(10);
  msg << "material update " << toString(r.status);
  if (r.status == UpdateStatus::SizeTooSmall) {
    msg << ": a band cannot open here, " << effectiveSizeProblem(r.refusedSize, params_.bandWidth, 1);
    return msg.str();
  }
  if (r.substeps > 1) msg << " after " << r.substeps << " sub-steps";
  msg << ", residual " << r.residual << " MPa";
  if (r.status == UpdateStatus::SnapBack) msg << " (snap_back: stop; release lets the band fail onto its stable branch)";
  return msg.str();
}

}  // namespace ecm
