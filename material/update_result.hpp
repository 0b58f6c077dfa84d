#pragma once
// The result of one constitutive update (the UMAT convention): stress, consistent tangent,
// dissipation of the increment, and whether the return converged.
#include "material/voigt.hpp"

namespace ecm {

enum class UpdateStatus {
  Converged,     // state committed
  NotConverged,  // Newton on traction continuity stalled; state unchanged (caller may sub-step)
  SnapBack,      // the band softens faster than the bulk unloads (C of Eq. (9) not positive):
                 // no equilibrium branch continues under strain control; state unchanged
  SizeTooSmall,  // a band would open where the effective size leaves no bulk: H below h (1 + 1e-6),
                 // or 2 h (1 + 1e-6) for a second band (docs/model.md); state unchanged
};

const char* toString(UpdateStatus s);

struct UpdateResult {
  Voigt stress = Voigt::Zero();
  Tangent tangent = Tangent::Zero();
  double dissipation = 0.0;  // energy dissipated in the increment per unit volume of the point (MPa = N mm/mm^3)
  UpdateStatus status = UpdateStatus::Converged;
  double residual = 0.0;  // final traction residual |(sigma - sigma_L) n| (MPa), 0 for closed-form models
  int iterations = 0;     // Newton iterations spent (0 for closed-form models)
  bool released = false;  // converged by a snap-back release (TwoPhasePoint::releaseSnapBack)
  int substeps = 1;       // equal sub-steps the increment was taken in (UpdateOptions::substepLevels)
  double refusedSize = 0.0;  // SizeTooSmall: the effective size H (mm) that was refused
  bool converged() const { return status == UpdateStatus::Converged; }
};

}  // namespace ecm
