#pragma once
// One material of a scene: which model, its parameters, and the one material-point update that
// every caller uses (the MPM's stress phase, the point driver's mixed control): the model
// dispatch, sub-stepping of an update that does not converge, the snap-back policy
// (UpdateOptions), and a band that cannot open in its effective size as a status.
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

// A view of one point's state wherever its parts are stored: a MaterialPoint, or the MPM's
// particle arrays with the band states in side arrays.
struct PointState {
  Voigt& strain;
  double* integrity = nullptr;       // SmearedCrack: x = 1 - D of the point (nullptr for other models)
  BandState* band = nullptr;         // Enriched: nullptr while intact
  BandState* secondBand = nullptr;   // Enriched with the second-band option: nullptr while it has none
  // Enriched, one band, no tangent: the band's secant response kept by the caller (rebuilt when
  // it is not the band's; material/secant_response.hpp), or nullptr: the predictor's solve.
  SecantResponse* secant = nullptr;
};

// The bands a point opened in an update, for the caller to store.
struct OpenedBands {
  std::optional<BandState> first, second;
  bool any() const { return first || second; }
};

class Material {
 public:
  explicit Material(const MaterialParams& p);

  // The material-point update. On Converged the state is committed (new bands in `opened`);
  // otherwise it is unchanged. A NotConverged update is retried in 2, 4, ... 2^levels equal
  // sub-steps (options.substepLevels), all of one size committed together or none; a snap-back
  // or a refused size is a property of the path, not of the step, and is not sub-stepped.
  // (Inline: the MPM calls it for every cracked point of every step; the sub-steps are not.)
  UpdateResult update(PointState state, const Voigt& strainIncrement, const EffectiveSize& size, OpenedBands& opened,
                      const UpdateOptions& options) const {
    UpdateResult r = updateOnce(state, strainIncrement, size, opened, options);
    if (r.status != UpdateStatus::NotConverged || options.substepLevels <= 0) return r;
    return substepped(state, strainIncrement, size, opened, options, r);
  }
  // The same on a MaterialPoint (its bands stored in place).
  UpdateResult update(MaterialPoint& point, const Voigt& strainIncrement, const EffectiveSize& size,
                      const UpdateOptions& options = {}) const;
  // Whether a point's stress is a : strain (Eq. (4) with no band): an elastic point, and an intact
  // enriched point, whichever update gave it (update() ends an intact increment with the same
  // product). Not a smeared-crack point (its integrity scales it) nor a cracked one. The explicit
  // MPM relies on it to store such stresses only when they are read (docs/model.md, "An intact
  // point's stress").
  bool stressFollowsStrain(bool cracked) const {
    return params_.model == ModelKind::LinearElastic || (params_.model == ModelKind::Enriched && !cracked);
  }
  // That stress, a : strain.
  Voigt intactStress(const Voigt& strain) const { return stiffness_ * strain; }
  // The closed-form stress, where there is one: an elastic point, or an intact enriched point
  // that does not reach onset in this increment (TwoPhasePoint::staysIntact), with a finite
  // stress. Then strain and stress are updated and it returns true; otherwise nothing changes
  // (the caller takes update()).
  // Inline: the explicit MPM calls it for nearly every point of every step.
  bool closedFormStress(const Voigt& increment, bool cracked, Voigt& strain, Voigt& stress) const {
    if (!stressFollowsStrain(cracked)) return false;
    const Voigt end = strain + increment;
    const Voigt s = intactStress(end);
    if (!s.allFinite() || (params_.model == ModelKind::Enriched && !std::get_if<TwoPhasePoint>(&model_)->staysIntact(s)))
      return false;
    strain = end;
    stress = s;
    return true;
  }
  // Why an update failed, in words (status, residual, the refused size and its bound).
  std::string explain(const UpdateResult& failed) const;
  // Stress of a point without changing it (for output and restarts).
  Voigt stress(const MaterialPoint& point) const;
  const MaterialParams& params() const { return params_; }
  const Tangent& stiffness() const { return stiffness_; }
  const TwoPhasePoint* enriched() const { return std::get_if<TwoPhasePoint>(&model_); }
  const SmearedCrack* smeared() const { return std::get_if<SmearedCrack>(&model_); }

 private:
  // One update of the point's model, without sub-steps.
  UpdateResult updateOnce(PointState s, const Voigt& d, const EffectiveSize& size, OpenedBands& opened,
                          const UpdateOptions& options) const {
    switch (params_.model) {
      case ModelKind::LinearElastic: {
        LinearElastic::State e{s.strain};
        const UpdateResult r = std::get_if<LinearElastic>(&model_)->update(e, d);
        s.strain = e.strain;
        return r;
      }
      case ModelKind::SmearedCrack: {
        SmearedCrack::State c{s.strain, *s.integrity};
        const UpdateResult r = std::get_if<SmearedCrack>(&model_)->update(c, d);
        s.strain = c.strain;
        *s.integrity = c.integrity;
        return r;
      }
      case ModelKind::Enriched: break;
    }
    const TwoPhasePoint& m = *std::get_if<TwoPhasePoint>(&model_);
    if (!m.opensSecondBand()) {
      if (!s.band) return m.updateIntact(s.strain, d, size, opened.first, options);
      return s.secant ? m.updateCracked(*s.band, *s.secant, s.strain, d, options) : m.updateCracked(*s.band, s.strain, d, options);
    }
    return s.band ? m.updateCracked(*s.band, s.secondBand, s.strain, d, size, opened.second, options)
                  : m.updateIntact(s.strain, d, size, opened.first, opened.second, options);
  }
  // The retries of an update that did not converge (`first`): 2, 4, ... 2^levels equal sub-steps.
  UpdateResult substepped(PointState s, const Voigt& d, const EffectiveSize& size, OpenedBands& opened,
                          const UpdateOptions& options, UpdateResult first) const;

  MaterialParams params_;
  Tangent stiffness_;
  std::variant<LinearElastic, SmearedCrack, TwoPhasePoint> model_;
};

}  // namespace ecm
