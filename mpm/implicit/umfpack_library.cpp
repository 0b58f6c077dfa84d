#include "mpm/implicit/umfpack_library.hpp"

#include <dlfcn.h>

#include <stdexcept>
#include <string>

namespace ecm::mpm {

namespace {

UmfpackLibrary load() {
  const char* name = ECM_UMFPACK_SONAME;  // the shared library the build found (mpm/CMakeLists.txt)
  void* handle = dlopen(name, RTLD_NOW | RTLD_LOCAL);
  if (handle == nullptr) {
    const char* why = dlerror();
    throw std::runtime_error(std::string("UMFPACK could not be loaded (") + (why ? why : name) +
                             "): install libsuitesparse-dev or set solver.linear_solver: sparselu");
  }
  const auto symbol = [&]<class Fn>(Fn& fn, const char* symbolName) {
    fn = reinterpret_cast<Fn>(dlsym(handle, symbolName));
    if (fn == nullptr) throw std::runtime_error(std::string("UMFPACK: ") + name + " has no " + symbolName);
  };
  UmfpackLibrary lib{};
  symbol(lib.defaults, "umfpack_di_defaults");
  symbol(lib.symbolic, "umfpack_di_symbolic");
  symbol(lib.numeric, "umfpack_di_numeric");
  symbol(lib.solve, "umfpack_di_solve");
  symbol(lib.freeSymbolic, "umfpack_di_free_symbolic");
  symbol(lib.freeNumeric, "umfpack_di_free_numeric");
  symbol(lib.getLunz, "umfpack_di_get_lunz");
  symbol(lib.getNumeric, "umfpack_di_get_numeric");
  return lib;  // the handle stays open for the process's life
}

}  // namespace

const UmfpackLibrary& umfpackLibrary() {
  static const UmfpackLibrary lib = load();  // a failed load throws and is tried again at the next call
  return lib;
}

}  // namespace ecm::mpm
