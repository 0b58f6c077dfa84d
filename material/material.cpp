#include "material/material.hpp"

#include <sstream>
#include <string>

#include "material/parameter_check.hpp"

namespace ecm {

const char* toString(ModelKind k) {
  switch (k) {
    case ModelKind::LinearElastic: return "linear_elastic";
    case ModelKind::SmearedCrack: return "smeared_crack";
    case ModelKind::Enriched: return "enriched";
  }
  return "?";
}

void MaterialParams::validate() const {
  if (model != ModelKind::Enriched && secondBand != SecondBandOption::Off)
    throw ParameterError(std::string("second_band: ") + toString(secondBand) + " needs the enriched model (model " +
                         toString(model) + " has no band)", "second_band");
  elastic.validate();
  requireInRange("density (t/mm^3)", density, 0.0, 1e300, true);
  if (model == ModelKind::LinearElastic) return;
  if (model == ModelKind::SmearedCrack && regularisedForSize > 0.0) {
    requireInRange("fracture_energy GF (N/mm)", fractureEnergy, 0.0, 1e300);
    BandDamageParams b = band();
    b.softeningModulus = 1.0;  // replaced by the regularised value
    b.validate();
    return;
  }
  band().validate();
  if (model == ModelKind::Enriched) enriched().validate();
}

namespace {
std::variant<LinearElastic, SmearedCrack, TwoPhasePoint> makeModel(const MaterialParams& p) {
  switch (p.model) {
    case ModelKind::LinearElastic: return LinearElastic(p.elastic);
    case ModelKind::SmearedCrack: {
      BandDamageParams b = p.band();
      if (p.regularisedForSize > 0.0)
        b.softeningModulus = regularisedSofteningModulus(b.law(), p.fractureEnergy, p.regularisedForSize);
      return SmearedCrack(b);
    }
    case ModelKind::Enriched: return TwoPhasePoint(p.enriched());
  }
  throw ParameterError("unknown model kind");
}
}  // namespace

namespace {
const MaterialParams& checked2D(const MaterialParams& p) {
  if (p.elastic.hypothesis == Hypothesis::ThreeDimensional)
    throw ParameterError("hypothesis three_dimensional needs a 3D caller (ecm-point, the UMAT; Material3D): "
                         "this one is 2D (plane_stress | plane_strain)", "hypothesis");
  p.validate();
  return p;
}
}  // namespace

Material::Material(const MaterialParams& p)
    : params_(checked2D(p)), stiffness_(elasticStiffness(p.elastic)), model_(makeModel(p)) {
  if (const auto* s = smeared()) params_.softeningModulus = s->law().law().softeningModulus;
}

UpdateResult Material::substepped(PointState s, const Voigt& d, const EffectiveSize& size, OpenedBands& opened,
                                  const UpdateOptions& options, UpdateResult r) const {
  // 2^level equal sub-steps on a copy of the state, committed only if every one converges.
  for (int level = 1; level <= options.substepLevels; ++level) {
    const int n = 1 << level;
    const Voigt sub = d / n;
    Voigt strain = s.strain;
    double integrity = s.integrity ? *s.integrity : 1.0;
    std::optional<BandState> band, second;
    if (s.band) band = *s.band;
    if (s.secondBand) second = *s.secondBand;
    double dissipation = 0.0;
    bool ok = true, released = false;
    for (int i = 0; i < n && ok; ++i) {
      OpenedBands o;
      r = updateOnce({strain, s.integrity ? &integrity : nullptr, band ? &*band : nullptr, second ? &*second : nullptr},
                     sub, size, o, options);
      if (o.first) band = o.first;
      if (o.second) second = o.second;
      ok = r.converged();
      dissipation += r.dissipation;
      released = released || r.released;
    }
    r.substeps = n;
    if (!ok) continue;
    s.strain = strain;
    if (s.integrity) *s.integrity = integrity;
    if (s.band)
      *s.band = *band;
    else
      opened.first = band;
    if (s.secondBand)
      *s.secondBand = *second;
    else
      opened.second = second;
    r.dissipation = dissipation;
    r.released = released;
    return r;
  }
  return r;
}

UpdateResult Material::update(MaterialPoint& point, const Voigt& d, const EffectiveSize& size,
                              const UpdateOptions& options) const {
  OpenedBands opened;
  const UpdateResult r =
      update({point.strain, &point.integrity, point.band ? &*point.band : nullptr,
              point.secondBand ? &*point.secondBand : nullptr},
             d, size, opened, options);
  if (opened.first) point.band = opened.first;
  if (opened.second) point.secondBand = opened.second;
  return r;
}

std::string Material::explain(const UpdateResult& r) const {
  std::ostringstream msg;
  msg.precision(10);
  msg << "material update " << toString(r.status);
  if (r.status == UpdateStatus::SizeTooSmall) {
    const int bands = params_.secondBand == SecondBandOption::Off ? 1 : 2;
    msg << ": a band cannot open here, " << effectiveSizeProblem(r.refusedSize, params_.bandWidth, bands);
    return msg.str();
  }
  if (r.substeps > 1) msg << " after " << r.substeps << " sub-steps";
  msg << ", residual " << r.residual << " MPa";
  if (r.status == UpdateStatus::SnapBack) msg << " (snap_back: stop; release lets the band fail onto its stable branch)";
  return msg.str();
}

Voigt Material::stress(const MaterialPoint& point) const {
  if (const auto* e = enriched(); e && point.band && point.secondBand)
    return e->stress(*point.band, *point.secondBand, point.strain);
  if (const auto* e = enriched(); e && point.band) return e->equilibrium(*point.band, point.strain, point.band->jump, false).stress;
  const double x = params_.model == ModelKind::SmearedCrack ? point.integrity : 1.0;
  return x * (stiffness_ * point.strain);
}

}  // namespace ecm
