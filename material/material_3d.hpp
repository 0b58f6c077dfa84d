#pragma once
// One material in 3D: the model dispatch, sub-stepping and the snap-back policy of
// Material::update (material/material.hpp) for six strain components. Models: linear elastic
// and enriched (one band); the smeared crack and the second band are refused with the reason.
#include <optional>
#include <string>
#include <variant>

#include "material/material.hpp"
#include "material/two_phase_point_3d.hpp"

namespace ecm {

// The state of one 3D material point: plain, fixed size.
struct MaterialPoint3 {
  Voigt6 strain = Voigt6::Zero();
  std::optional<BandState3> band;  // Enriched: present once cracked
  double damage() const { return band ? band->damage() : 0.0; }
};

class Material3D {
 public:
  // Throws ParameterError for a model or option the 3D point does not offer. The elastic
  // hypothesis must be ThreeDimensional.
  explicit Material3D(const MaterialParams& p);

  // The material-point update: committed on Converged, unchanged otherwise. A NotConverged
  // update is retried in 2, 4, ... 2^substepLevels equal sub-steps, all committed or none.
  UpdateResult3 update(MaterialPoint3& point, const Voigt6& strainIncrement, const EffectiveSize3& size,
                       const UpdateOptions& options = {}) const;
  // Stress and stored energy (per unit volume: bulk and band) of a committed state.
  Voigt6 stress(const MaterialPoint3& point) const;
  double storedEnergy(const MaterialPoint3& point) const;
  std::string explain(const UpdateResult3& failed) const;

  const MaterialParams& params() const { return params_; }
  const Tangent6& stiffness() const { return stiffness_; }
  const TwoPhasePoint3D* enriched() const { return enriched_ ? &*enriched_ : nullptr; }

 private:
  UpdateResult3 updateOnce(MaterialPoint3& point, const Voigt6& d, const EffectiveSize3& size,
                           const UpdateOptions& options) const;

  MaterialParams params_;
  Tangent6 stiffness_;
  std::optional<TwoPhasePoint3D> enriched_;
};

}  // namespace ecm
