#pragma once
// The result of one 3D constitutive update: the 3D counterpart of material/update_result.hpp
// (the same statuses and meaning, six stress components).
#include "material/update_result.hpp"
#include "material/voigt3.hpp"

namespace ecm {

struct UpdateResult3 {
  Voigt6 stress = Voigt6::Zero();
  Tangent6 tangent = Tangent6::Zero();
  double dissipation = 0.0;  // energy dissipated in the increment per unit volume of the point (MPa)
  UpdateStatus status = UpdateStatus::Converged;
  double residual = 0.0;     // final traction residual |(sigma - sigma_L) n| (MPa)
  int iterations = 0;        // Newton iterations spent
  bool released = false;     // converged by a snap-back release
  int substeps = 1;          // equal sub-steps the increment was taken in
  double refusedSize = 0.0;  // SizeTooSmall: the effective size H (mm) that was refused
  bool converged() const { return status == UpdateStatus::Converged; }
};

}  // namespace ecm
