/* The Abaqus user-material subroutine of ecm (libecm_umat.so): C ABI, Fortran calling
   convention (every argument by reference, column-major arrays, CMNAME's length appended).
   Units: mm, N, MPa. Layouts of PROPS and STATEV: umat/umat_layout.hpp and docs/fe-codes.md. */
#ifndef ECM_UMAT_H
#define ECM_UMAT_H
#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

__attribute__((visibility("default"))) void umat_(double* stress, double* statev, double* ddsdde, double* sse, double* spd, double* scd, double* rpl,
           double* ddsddt, double* drplde, double* drpldt, const double* stran, const double* dstran,
           const double* time, const double* dtime, const double* temp, const double* dtemp, const double* predef,
           const double* dpred, const char* cmname, const int* ndi, const int* nshr, const int* ntens,
           const int* nstatv, const double* props, const int* nprops, const double* coords, const double* drot,
           double* pnewdt, const double* celent, const double* dfgrd0, const double* dfgrd1, const int* noel,
           const int* npt, const int* layer, const int* kspt, const int* kstep, const int* kinc, size_t cmname_len);

#ifdef __cplusplus
}
#endif
#endif
