#include "material/update_result.hpp"

namespace ecm {

const char* toString(UpdateStatus s) {
  switch (s) {
    case UpdateStatus::Converged: return "converged";
    case UpdateStatus::NotConverged: return "not converged";
    case UpdateStatus::SnapBack: return "snap-back";
    case UpdateStatus::SizeTooSmall: return "effective size too small";
  }
  return "?";
}

}  // namespace ecm
