// The failure kinds' one table (mpm/core/errors.hpp).
#include "mpm/core/errors.hpp"

#include <algorithm>

namespace ecm::mpm {

const std::array<FailureKindInfo, 11> kFailureKinds{{
    {FailureKind::LeftGrid, "left_grid", 10, "a particle or its shape-function support left the background grid"},
    {FailureKind::NotFinite, "not_finite", 11, "NaN or infinity in a particle's velocity, position or stress"},
    {FailureKind::MaterialFailure, "material_update", 12, "a material update did not converge even after sub-stepping"},
    {FailureKind::SnapBack, "snap_back", 13, "a material snap-back under snap_back: stop"},
    {FailureKind::NewtonNotConverged, "newton_not_converged", 14, "implicit: Newton did not converge on the smallest piece"},
    {FailureKind::SingularTangent, "singular_tangent", 15, "implicit: the tangent was singular on the smallest piece"},
    {FailureKind::OnsetOvershoot, "onset_overshoot", 16, "implicit: the smallest piece carried a point too far past its onset"},
    {FailureKind::ControlBlind, "control_blind", 17, "implicit, indirect control: the opening does not change with the load factor"},
    {FailureKind::DampingWork, "damping_work", 18, "explicit: the damping's work passed the energy put into the run"},
    {FailureKind::WorkImbalance, "work_imbalance", 19, "implicit: the external and internal works parted"},
    {FailureKind::Output, "output", 20, "a file could not be written once the run had begun"},
}};

const FailureKindInfo& infoOf(FailureKind k) {
  return *std::find_if(kFailureKinds.begin(), kFailureKinds.end(), [k](const FailureKindInfo& i) { return i.kind == k; });
}

}  // namespace ecm::mpm
