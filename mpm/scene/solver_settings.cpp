// The names of the solver settings' choices and what the build has (mpm/scene/solver_settings.hpp).
#include "mpm/scene/solver_settings.hpp"

namespace ecm::mpm {

const char* toString(UpdateScheme s) {
  switch (s) {
    case UpdateScheme::USF: return "usf";
    case UpdateScheme::USL: return "usl";
    case UpdateScheme::MUSL: return "musl";
  }
  return "?";
}

const char* toString(LinearSolverKind k) {
  switch (k) {
    case LinearSolverKind::SparseLU: return "sparselu";
    case LinearSolverKind::Umfpack: return "umfpack";
    case LinearSolverKind::Amg: return "amg";
  }
  return "?";
}

bool available(LinearSolverKind k) {
  switch (k) {
    case LinearSolverKind::SparseLU: return true;
#ifdef ECM_HAVE_UMFPACK
    case LinearSolverKind::Umfpack: return true;
#endif
#ifdef ECM_HAVE_HYPRE
    case LinearSolverKind::Amg: return true;
#endif
    default: return false;
  }
}

const char* toString(CrackPathRule r) { return r == CrackPathRule::Tracked ? "tracked" : "free"; }

}  // namespace ecm::mpm
