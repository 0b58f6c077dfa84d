#pragma once
// The PROPS and STATEV layouts of ecm's UMAT (docs/fe-codes.md), and the pure C++ update behind
// umat_(): the material from PROPS, the point from STATEV and STRAN, one Material3D (NTENS 6, 4)
// or 2D plane-stress Material (NTENS 3) update, the results back in Abaqus's component order.
#include <string>
#include <vector>

#include "material/material.hpp"
#include "material/material_3d.hpp"

namespace ecm::umat {

// PROPS (1-based in the input deck, 0-based here). Units: mm, N, MPa.
enum Prop : int {
  kModel = 0,          // 1: enriched, 0: linear elastic (no band; PROPS 4-8 ignored but present)
  kYoungsModulus,      // E (MPa)
  kPoissonRatio,       // nu
  kTensileStrength,    // f_t' (MPa)
  kSofteningModulus,   // E_p (MPa)
  kSofteningExponent,  // n (0 < n < 0.5)
  kBandWidth,          // h (mm)
  kEffectiveSize,      // H (mm) > 0, or 0: the caller's CELENT (Abaqus; CalculiX gives none)
  kSnapBack,           // 0: stop (PNEWDT < 1 at a snap-back), 1: release onto the stable branch
  kSubstepLevels,      // optional (default 10): a non-converging update is retried in 2 .. 2^levels sub-steps
  kPropCount
};
inline constexpr int kMinProps = kSubstepLevels;  // PROPS 1-9 required, 10 optional

// STATEV (1-based in docs, 0-based here). Vectors in ecm's component order: normal and jump
// (x, y, z), onset strain (xx, yy, zz, yz, xz, xy; engineering shears).
enum State : int {
  kCracked = 0,      // 0 intact, 1 cracked
  kIntegrity,        // x = 1 - D of the band
  kNormal,           // 3: n
  kJump = kNormal + 3,          // 3: [u] (mm)
  kOnsetStrain = kJump + 3,     // 6: eps_on
  kVolumeFraction = kOnsetStrain + 6,  // f = h / H
  kDissipation,      // accumulated f int Y dD per unit volume (MPa)
  kDamage,           // D = 1 - x (output only)
  kStateCount        // NSTATV must be at least this (17)
};

struct Inputs {
  const double* stran;   // strain at the start, Abaqus order, engineering shears
  const double* dstran;  // its increment
  int ndi, nshr, ntens, nstatv, nprops;
  const double* props;
  double celent;         // the element's characteristic length (0 if the caller gives none)
  const double* drot = nullptr;  // the rotation increment R (3 x 3, column-major), or none: the identity
};

// A cracked point's band state in STATEV carried along the increment's rigid rotation R (DROT,
// with NLGEOM): n <- R n, [u] <- R [u], eps_on <- R eps_on R^T, as the caller rotates STRESS and
// STRAN (docs/fe-codes.md). An intact point has nothing to rotate.
void rotateBandState(double* statev, const double* drot);

struct Outputs {
  double* stress;  // NTENS, Abaqus order
  double* statev;  // NSTATV
  double* ddsdde;  // NTENS x NTENS, column-major
  double* sse;
  double* spd;
  double* pnewdt;
};

// Why PROPS (or NDI/NSHR/NSTATV) cannot be used, "" if they can: a sentence naming the entry,
// its value and the accepted range.
std::string propsProblem(const Inputs& in);
// The material PROPS describe (after propsProblem() is empty).
MaterialParams materialFromProps(const double* props, int nprops, Hypothesis hypothesis);

// One update. Returns "" on success; otherwise the reason: bad input (the caller stops) when
// `fatal` is set, else a failed update (PNEWDT set below 1, outputs at the start state).
std::string update(const Inputs& in, const Outputs& out, bool& fatal);

// Abaqus component index -> ecm's 3D Voigt index (shears 12, 13, 23 -> xy, xz, yz).
inline constexpr int kAbaqusToEcm6[6] = {0, 1, 2, 5, 4, 3};
inline constexpr int kAbaqusToEcm4[4] = {0, 1, 2, 5};  // 11, 22, 33, 12 (plane strain, axisymmetric)

}  // namespace ecm::umat
