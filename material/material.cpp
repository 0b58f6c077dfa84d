#include "material/material.hpp"

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
                         toString(model) + " has no band)");
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

Material::Material(const MaterialParams& p)
    : params_((p.validate(), p)), stiffness_(elasticStiffness(p.elastic)), model_(makeModel(p)) {
  if (const auto* s = smeared()) params_.softeningModulus = s->law().law().softeningModulus;
}

UpdateResult Material::update(MaterialPoint& point, const Voigt& increment, const EffectiveSize& size,
                              const UpdateOptions& options) const {
  struct Visitor {
    MaterialPoint& p;
    const Voigt& d;
    const EffectiveSize& size;
    const UpdateOptions& options;
    UpdateResult operator()(const LinearElastic& m) const {
      LinearElastic::State s{p.strain};
      UpdateResult r = m.update(s, d);
      p.strain = s.strain;
      return r;
    }
    UpdateResult operator()(const SmearedCrack& m) const {
      SmearedCrack::State s{p.strain, p.integrity};
      UpdateResult r = m.update(s, d);
      p.strain = s.strain;
      p.integrity = s.integrity;
      return r;
    }
    UpdateResult operator()(const TwoPhasePoint& m) const {
      if (!m.opensSecondBand())
        return p.band ? m.updateCracked(*p.band, p.strain, d, options) : m.updateIntact(p.strain, d, size, p.band, options);
      if (!p.band) return m.updateIntact(p.strain, d, size, p.band, p.secondBand, options);
      std::optional<BandState> opened;
      const UpdateResult r = m.updateCracked(*p.band, p.secondBand ? &*p.secondBand : nullptr, p.strain, d, size, opened, options);
      if (opened) p.secondBand = opened;
      return r;
    }
  };
  return std::visit(Visitor{point, increment, size, options}, model_);
}

Voigt Material::stress(const MaterialPoint& point) const {
  if (const auto* e = enriched(); e && point.band && point.secondBand)
    return e->stress(*point.band, *point.secondBand, point.strain);
  if (const auto* e = enriched(); e && point.band) return e->equilibrium(*point.band, point.strain, point.band->jump, false).stress;
  const double x = params_.model == ModelKind::SmearedCrack ? point.integrity : 1.0;
  return x * (stiffness_ * point.strain);
}

}  // namespace ecm
