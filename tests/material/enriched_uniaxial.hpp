#pragma once
// Test helper: an enriched point of effective size H driven in uniaxial stress.
#include <cmath>
#include <vector>

#include "material/two_phase_point.hpp"
#include "../paper_constants.hpp"
#include "uniaxial.hpp"

namespace ecm::test {

struct EnrichedRun {
  TwoPhasePoint model;
  EnrichedState state;
  EffectiveSize size;
  double dissipated = 0.0;
  double work = 0.0;  // int sigma_xx d eps_xx (trapezoid)
  double peak = 0.0;
  Voigt stress = Voigt::Zero();

  EnrichedRun(const EnrichedParams& p, double effectiveSize) : model(p), size(EffectiveSize::fixed(effectiveSize)) {}

  TrialUpdate trial() {
    return [this](const Voigt& d, bool commit) {
      EnrichedState s = state;
      const UpdateResult r = model.update(s, d, size);
      if (commit) {
        state = s;
        dissipated += r.dissipation;
      }
      return r;
    };
  }
  // One uniaxial-stress increment of eps_xx; false if the update failed (e.g. snap-back).
  // The lateral-stress tolerance grows with the effective stress a:eps (round-off at huge strains).
  bool step(double dExx, double tol = 1e-11) {
    const double scale = 1.0 + model.stiffness()(0, 0) * std::abs(state.strain[0]);
    const auto r = uniaxialStressStep(trial(), dExx, model.stiffness(), tol * scale);
    if (!r) return false;
    work += 0.5 * (stress[0] + r->stress[0]) * dExx;
    stress = r->stress;
    peak = std::max(peak, stress[0]);
    return true;
  }
};

}  // namespace ecm::test
