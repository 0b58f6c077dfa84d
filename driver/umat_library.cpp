#include "driver/umat_library.hpp"

#include <dlfcn.h>

#include <array>
#include <stdexcept>

namespace ecm::driver {

UmatLibrary::UmatLibrary(const std::filesystem::path& file) : file_(file) {
  // A path without a '/' would be looked up on the loader's search path, not where the user is.
  const std::filesystem::path where = file.has_parent_path() ? file : std::filesystem::path(".") / file;
  handle_ = dlopen(where.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle_) {
    const char* why = dlerror();
    throw std::runtime_error("cannot load the UMAT library " + file.string() + ": " + (why ? why : "unknown reason"));
  }
  for (const char* name : {"umat_", "umat", "UMAT"}) {
    if (void* symbol = dlsym(handle_, name)) {
      umat_ = reinterpret_cast<Entry>(symbol);
      entry_ = name;
      return;
    }
  }
  dlclose(handle_);
  handle_ = nullptr;
  throw std::runtime_error("the library " + file.string() +
                           " has no UMAT entry (looked for the symbols umat_, umat and UMAT; a Fortran SUBROUTINE UMAT "
                           "compiled by gfortran is umat_)");
}

UmatLibrary::~UmatLibrary() {
  if (handle_) dlclose(handle_);
}

void UmatLibrary::call(UmatCall& c, const std::vector<double>& props, const std::string& materialName) const {
  constexpr int ndi = 3, nshr = 3, ntens = 6, noel = 1, npt = 1, layer = 1, kspt = 1;
  const int nstatv = static_cast<int>(c.statev.size()), nprops = static_cast<int>(props.size());
  const std::array<int, 4> kstep{c.kstep, 1, 0, 0};  // step, procedure (static), NLGEOM off, perturbation off
  std::array<char, 80> cmname{};
  cmname.fill(' ');  // a Fortran CHARACTER*80: blank-padded
  for (std::size_t i = 0; i < materialName.size() && i < cmname.size(); ++i) cmname[i] = materialName[i];
  double rpl = 0.0, drpldt = 0.0, temp = 0.0, dtemp = 0.0, predef = 0.0, dpred = 0.0;
  double ddsddt[6] = {}, drplde[6] = {}, coords[3] = {}, drot[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  c.stress.resize(ntens, 0.0);
  c.ddsdde.assign(ntens * ntens, 0.0);
  umat_(c.stress.data(), c.statev.data(), c.ddsdde.data(), &c.sse, &c.spd, &c.scd, &rpl, ddsddt, drplde, &drpldt,
        c.stran.data(), c.dstran.data(), c.time, &c.dtime, &temp, &dtemp, &predef, &dpred, cmname.data(), &ndi, &nshr,
        &ntens, &nstatv, props.data(), &nprops, coords, drot, &c.pnewdt, &c.celent, c.dfgrd0, c.dfgrd1, &noel, &npt,
        &layer, &kspt, kstep.data(), &c.kinc, cmname.size());
}

}  // namespace ecm::driver
