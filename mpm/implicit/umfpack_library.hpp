#pragma once
// UMFPACK's C functions (double values, int indices), from its shared library loaded at the first
// call: linking it would make every run of ecm-mpm carry UMFPACK, CHOLMOD, the BLAS, LAPACK and
// the Fortran run-time in memory (3.6 MB resident, docs/performance.md), though only implicit
// scenes use them. Built only when the build found UMFPACK (ECM_HAVE_UMFPACK).
#include <umfpack.h>

namespace ecm::mpm {

struct UmfpackLibrary {
  decltype(&umfpack_di_defaults) defaults;
  decltype(&umfpack_di_symbolic) symbolic;
  decltype(&umfpack_di_numeric) numeric;
  decltype(&umfpack_di_solve) solve;
  decltype(&umfpack_di_free_symbolic) freeSymbolic;
  decltype(&umfpack_di_free_numeric) freeNumeric;
  decltype(&umfpack_di_get_lunz) getLunz;
  decltype(&umfpack_di_get_numeric) getNumeric;
};

// The library, loaded once; throws std::runtime_error naming it and the loader's reason when it
// cannot be loaded (the scene can ask for `linear_solver: sparselu` instead).
const UmfpackLibrary& umfpackLibrary();

}  // namespace ecm::mpm
