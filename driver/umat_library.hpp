#pragma once
// A UMAT loaded from a shared library at run time (ecm-point --umat LIB.so): ecm's own
// libecm_umat.so or any other with Abaqus's UMAT interface (Fortran convention: every argument
// by reference, column-major arrays, CMNAME's length appended). The entry is looked up as
// `umat_` (gfortran, and C libraries such as ecm's), then `umat` and `UMAT`.
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

namespace ecm::driver {

// What one call passes and gets back (Abaqus's names; NTENS = 6, Abaqus's component order
// 11, 22, 33, 12, 13, 23; engineering shears).
struct UmatCall {
  std::vector<double> stress;  // in: at the start; out: at the end (6)
  std::vector<double> statev;  // in: at the start; out: at the end (NSTATV)
  std::vector<double> ddsdde = std::vector<double>(36, 0.0);  // out: d stress / d strain, column-major
  double sse = 0.0, spd = 0.0, scd = 0.0;  // energies per unit volume (MPa), in and out
  std::vector<double> stran, dstran;       // strain at the start and its increment (6)
  double time[2] = {0.0, 0.0};             // step time and total time at the start
  double dtime = 1.0;
  double pnewdt = 1.0;                     // in: 1; out below 1: the UMAT asks for a smaller increment
  double celent = 0.0;                     // CELENT (mm)
  double dfgrd0[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, dfgrd1[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  int kstep = 1, kinc = 1;
};

class UmatLibrary {
 public:
  // Loads `file` and finds its entry; throws std::runtime_error naming the file and why not.
  explicit UmatLibrary(const std::filesystem::path& file);
  ~UmatLibrary();
  UmatLibrary(const UmatLibrary&) = delete;
  UmatLibrary& operator=(const UmatLibrary&) = delete;

  // One call with PROPS, the material's name (CMNAME) and the point's CELENT (COORDS 0,
  // DROT the identity, NOEL = NPT = 1).
  void call(UmatCall& c, const std::vector<double>& props, const std::string& materialName) const;

  const std::filesystem::path& file() const { return file_; }
  const std::string& entry() const { return entry_; }

 private:
  using Entry = void (*)(double*, double*, double*, double*, double*, double*, double*, double*, double*, double*,
                         const double*, const double*, const double*, const double*, const double*, const double*,
                         const double*, const double*, const char*, const int*, const int*, const int*, const int*,
                         const double*, const int*, const double*, const double*, double*, const double*, const double*,
                         const double*, const int*, const int*, const int*, const int*, const int*, const int*,
                         std::size_t);
  std::filesystem::path file_;
  std::string entry_;
  void* handle_ = nullptr;
  Entry umat_ = nullptr;
};

}  // namespace ecm::driver
