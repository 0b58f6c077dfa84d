#pragma once
// One increment of a point under mixed strain/stress control: the strain-controlled components
// get their increment, the stress-controlled ones are found by Newton with the material's
// consistent tangent (residual <= tolerance), with the elastic stiffness as a fallback where
// the tangent jumps (onset). A material update that fails to converge is sub-stepped.
#include <array>
#include <functional>

#include "driver/load_path.hpp"
#include "material/material.hpp"

namespace ecm::driver {

struct MixedTarget {
  std::array<Control, 3> control{Control::Strain, Control::Strain, Control::Strain};
  Voigt strainIncrement = Voigt::Zero();  // used for strain-controlled components
  Voigt stress = Voigt::Zero();           // end-of-increment stress for stress-controlled ones
};

struct StepOutcome {
  UpdateResult result;       // stress, tangent, status of the final (sub)step
  Voigt strainIncrement = Voigt::Zero();  // the full increment applied (all components)
  double dissipation = 0.0;  // sum over sub-steps
  double controlResidual = 0.0;  // |sigma_s - target_s| (MPa)
  int iterations = 0;        // mixed-control Newton iterations, summed over sub-steps
  int substeps = 1;
  bool converged() const { return result.converged(); }
};

struct MixedControlSettings {
  double tolerance = 1e-8;   // on |sigma_s - target_s|, MPa (callers use 1e-8 f_t')
  int maxIterations = 200;
  int maxSubstepLevels = 10; // up to 2^10 sub-steps of a failing increment
};

// The strain increment that meets the target with the stiffness k (the elastic one for the
// predictor): strain-controlled components as given, stress-controlled ones from
// k_ss d_s = (target - current)_s - k_sk d_k. Exact for an elastic point.
Voigt elasticMixedIncrement(const Tangent& k, const Voigt& currentStress, const MixedTarget& target);

// One constitutive update of a point (normally Material::update at the point's H).
using PointUpdate = std::function<UpdateResult(MaterialPoint& point, const Voigt& strainIncrement)>;

// Commits the increment to `point` and returns its outcome; on failure `point` is unchanged.
// `elastic` is the fallback stiffness for the stress-controlled components.
StepOutcome mixedControlStep(const PointUpdate& update, const Tangent& elastic, MaterialPoint& point,
                             const Voigt& currentStress, const MixedTarget& target, const MixedControlSettings& s);
inline StepOutcome mixedControlStep(const Material& material, MaterialPoint& point, const Voigt& currentStress,
                                    const MixedTarget& target, const EffectiveSize& size, const MixedControlSettings& s,
                                    SnapBackPolicy policy) {
  UpdateOptions options(policy);
  for (int i = 0; i < 3; ++i)
    if (target.control[i] == Control::Stress) options.stressControlled |= 1u << i;
  return mixedControlStep([&](MaterialPoint& p, const Voigt& d) { return material.update(p, d, size, options); },
                          material.stiffness(), point, currentStress, target, s);
}

}  // namespace ecm::driver
