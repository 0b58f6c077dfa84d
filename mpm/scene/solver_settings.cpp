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

const char* toString(LinearSolverKind k) { return k == LinearSolverKind::Umfpack ? "umfpack" : "sparselu"; }

bool available([[maybe_unused]] LinearSolverKind k) {
#ifdef ECM_HAVE_UMFPACK
  return true;
#else
  return k == LinearSolverKind::SparseLU;
#endif
}

}  // namespace ecm::mpm
