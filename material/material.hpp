#pragma once
// One material of a scene: which model, its parameters, and a uniform update over the models.
// Built from an already-validated parameter struct (the YAML edge lives in io/).
#include <optional>
#include <string>
#include <variant>

#include "material/two_phase_point.hpp"
#include "material/linear_elastic.hpp"
#include "material/parameter_check.hpp"
#include "material/smeared_crack.hpp"

namespace ecm {

enum class ModelKind { LinearElastic, SmearedCrack, Enriched };
const char* toString(ModelKind k);

struct MaterialParams {
  std::string name;
  ModelKind model = ModelKind::Enriched;
  ElasticParams elastic;           // E (MPa), nu, plane stress / plane strain
  double density = 0.0;            // t/mm^3 (only MPM needs it; 0 = not given)
  double tensileStrength = 0.0;    // f_t' (MPa)
  double softeningModulus = 0.0;   // E_p (MPa)
  double softeningExponent = 0.0;  // n
  double bandWidth = 0.0;          // h (mm), enriched model only
  SecondBandOption secondBand = SecondBandOption::Off;  // enriched model only (docs/model.md)
  double fractureEnergy = 0.0;     // G_F (N/mm): informational, or the target of smeared regularisation
  // SmearedCrack only: if > 0, E_p is replaced by the crack-band value for this element size H.
  double regularisedForSize = 0.0;

  BandDamageParams band() const { return {elastic, tensileStrength, softeningModulus, softeningExponent}; }
  EnrichedParams enriched() const { return {band(), bandWidth, secondBand}; }
  void validate() const;  // throws ParameterError naming the parameter, value and range
};

// The state of one material point under any model: plain, fixed size.
struct MaterialPoint {
  Voigt strain = Voigt::Zero();
  double integrity = 1.0;         // SmearedCrack: x = 1 - D of the whole point
  std::optional<BandState> band;        // Enriched: present once cracked
  std::optional<BandState> secondBand;  // Enriched with the second-band option: once it opened
  double damage() const { return band ? band->damage() : 1.0 - integrity; }
};

class Material {
 public:
  explicit Material(const MaterialParams& p);
  UpdateResult update(MaterialPoint& point, const Voigt& strainIncrement, const EffectiveSize& size,
                      const UpdateOptions& options = {}) const;
  // Stress of a point without changing it (for output and restarts).
  Voigt stress(const MaterialPoint& point) const;
  const MaterialParams& params() const { return params_; }
  const Tangent& stiffness() const { return stiffness_; }
  const TwoPhasePoint* enriched() const { return std::get_if<TwoPhasePoint>(&model_); }
  const SmearedCrack* smeared() const { return std::get_if<SmearedCrack>(&model_); }

 private:
  MaterialParams params_;
  Tangent stiffness_;
  std::variant<LinearElastic, SmearedCrack, TwoPhasePoint> model_;
};

}  // namespace ecm
