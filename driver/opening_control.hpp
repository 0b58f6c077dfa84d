#pragma once
// One increment of a cracked enriched point driven by its band's normal opening [u].n: the
// path parameter that traces a snap-back branch. Unknowns: the load factor lambda along the
// strain-controlled direction, the stress-controlled strains and the sliding jump; equations:
// the stress targets and traction continuity, Eq. (6). Newton with the exact Jacobian.
#include "driver/mixed_control.hpp"

namespace ecm::driver {

struct OpeningTarget {
  std::array<Control, 3> control{Control::Strain, Control::Strain, Control::Strain};
  Voigt direction = Voigt::Zero();  // strain-controlled components: eps += lambda * direction
  Voigt stress = Voigt::Zero();     // stress-controlled components: their end-of-increment values
  double normalJump = 0.0;          // [u].n at the end of the increment (mm)
};

struct OpeningOutcome {
  StepOutcome step;
  double loadFactor = 0.0;  // lambda of this increment
};

// Requires point.band. Commits on success; on failure the point is unchanged.
OpeningOutcome openingControlStep(const TwoPhasePoint& model, MaterialPoint& point, const OpeningTarget& target,
                                  double tolerance, int maxIterations = 100);

}  // namespace ecm::driver
