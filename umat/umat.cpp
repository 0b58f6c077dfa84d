// ecm's Abaqus UMAT (umat/umat.h): PROPS and STATEV as in umat/umat_layout.hpp, one material
// point update per call, the consistent tangent of Eq. (10) as DDSDDE (docs/fe-codes.md).
#include "umat/umat.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <sstream>

#include "umat/call_trace.hpp"
#include "umat/umat_layout.hpp"

namespace ecm::umat {

namespace {

std::string propName(int i) {
  static const char* names[] = {"model (1 enriched, 0 linear elastic)", "E (MPa)", "nu", "f_t' (MPa)", "E_p (MPa)",
                                "n", "h (mm)", "H (mm, 0: CELENT)", "snap_back (0 stop, 1 release)", "substep levels"};
  return "PROPS(" + std::to_string(i + 1) + ") " + names[i];
}

bool isInteger(double v, double lo, double hi) { return v >= lo && v <= hi && v == std::floor(v); }

bool enriched(const double* props) { return props[kModel] == 1.0; }

// The materials of the PROPS last seen on this thread (an FE code calls with the same PROPS for
// every point of a material): built once, not per call.
struct Cache {
  std::vector<double> props;
  Hypothesis hypothesis = Hypothesis::PlaneStress;
  std::optional<Material3D> m3;
  std::optional<Material> m2;
};

Cache& materialFor(const Inputs& in, Hypothesis hypothesis) {
  thread_local Cache cache;
  const std::vector<double> props(in.props, in.props + std::min(in.nprops, static_cast<int>(kSubstepLevels)));
  if (cache.props != props || cache.hypothesis != hypothesis || (!cache.m3 && !cache.m2)) {
    cache.m3.reset();
    cache.m2.reset();
    const MaterialParams p = materialFromProps(in.props, in.nprops, hypothesis);
    if (hypothesis == Hypothesis::ThreeDimensional)
      cache.m3.emplace(p);
    else
      cache.m2.emplace(p);
    cache.props = props;
    cache.hypothesis = hypothesis;
  }
  return cache;
}

double effectiveSizeOf(const Inputs& in) { return in.props[kEffectiveSize] > 0.0 ? in.props[kEffectiveSize] : in.celent; }

// 2D plane-stress energies: (1 - f) sigma : eps_b / 2 + f sigma_L : eps_L / 2.
double storedEnergy2D(const Material& m, const MaterialPoint& p) {
  if (!p.band) return 0.5 * p.strain.dot(m.stiffness() * p.strain);
  const BandEquilibrium eq = m.enriched()->equilibrium(*p.band, p.strain, p.band->jump, false);
  const double f = p.band->volumeFraction;
  const Voigt bulk = (p.strain - f * eq.bandStrain) / (1.0 - f);  // Eq. (2)
  return 0.5 * ((1.0 - f) * eq.stress.dot(bulk) + f * eq.band.stress.dot(eq.bandStrain));
}

void writeBand(double* s, bool cracked, const Vec3& n, const Vec3& jump, const Voigt6& onset, double x, double f) {
  s[kCracked] = cracked ? 1.0 : 0.0;
  s[kIntegrity] = x;
  for (int i = 0; i < 3; ++i) s[kNormal + i] = n[i], s[kJump + i] = jump[i];
  for (int i = 0; i < 6; ++i) s[kOnsetStrain + i] = onset[i];
  s[kVolumeFraction] = f;
  s[kDamage] = 1.0 - x;
}

BandState3 readBand3(const double* s) {
  BandState3 b;
  b.integrity = s[kIntegrity];
  for (int i = 0; i < 3; ++i) b.crackNormal[i] = s[kNormal + i], b.jump[i] = s[kJump + i];
  for (int i = 0; i < 6; ++i) b.onsetStrain[i] = s[kOnsetStrain + i];
  b.volumeFraction = s[kVolumeFraction];
  return b;
}

// A converged update whose stress, tangent or energy is not a number: the strains are beyond what
// a double holds once multiplied by the stiffness. Failed like a non-converging update.
std::string overflow(const Inputs& in) {
  double largest = 0.0;
  for (int i = 0; i < in.ntens; ++i) largest = std::max({largest, std::abs(in.stran[i]), std::abs(in.stran[i] + in.dstran[i])});
  std::ostringstream msg;
  msg << "the stress overflows (largest strain component " << largest << ")";
  return msg.str();
}

std::string update3D(const Inputs& in, const Outputs& out, const Material3D& m, const UpdateOptions& options, double bigH) {
  const bool full = in.ntens == 6;
  const int* map = full ? kAbaqusToEcm6 : kAbaqusToEcm4;
  MaterialPoint3 p;
  Voigt6 d = Voigt6::Zero();
  for (int i = 0; i < in.ntens; ++i) p.strain[map[i]] = in.stran[i], d[map[i]] = in.dstran[i];
  if (out.statev[kCracked] == 1.0) p.band = readBand3(out.statev);
  const MaterialPoint3 start = p;
  const UpdateResult3 r = m.update(p, d, EffectiveSize3::fixed(bigH), options);
  const bool finite = r.stress.allFinite() && r.tangent.allFinite() && std::isfinite(m.storedEnergy(p));
  const bool ok = r.converged() && finite;
  const Voigt6 stress = ok ? r.stress : m.stress(start);
  for (int i = 0; i < in.ntens; ++i) {
    out.stress[i] = stress[map[i]];
    for (int j = 0; j < in.ntens; ++j) out.ddsdde[i + j * in.ntens] = ok ? r.tangent(map[i], map[j]) : m.stiffness()(map[i], map[j]);
  }
  if (!ok) return finite ? m.explain(r) : overflow(in);
  if (p.band) writeBand(out.statev, true, p.band->crackNormal, p.band->jump, p.band->onsetStrain, p.band->integrity, p.band->volumeFraction);
  else out.statev[kDamage] = 0.0;  // an output: written whatever the caller set
  out.statev[kDissipation] += r.dissipation;
  *out.sse = m.storedEnergy(p);
  *out.spd = out.statev[kDissipation];
  return "";
}

std::string updatePlaneStress(const Inputs& in, const Outputs& out, const Material& m, const UpdateOptions& options,
                              double bigH) {
  MaterialPoint p;
  const Voigt d(in.dstran[0], in.dstran[1], in.dstran[2]);  // 11, 22, 12: ecm's 2D order
  p.strain = Voigt(in.stran[0], in.stran[1], in.stran[2]);
  if (out.statev[kCracked] == 1.0) {
    const BandState3 b = readBand3(out.statev);
    BandState b2;
    b2.crackNormal = Vec2(b.crackNormal[0], b.crackNormal[1]);
    b2.jump = Vec2(b.jump[0], b.jump[1]);
    b2.onsetStrain = Voigt(b.onsetStrain[0], b.onsetStrain[1], b.onsetStrain[5]);
    b2.integrity = b.integrity;
    b2.volumeFraction = b.volumeFraction;
    p.band = b2;
  }
  const MaterialPoint start = p;
  const UpdateResult r = m.update(p, d, EffectiveSize::fixed(bigH), options);
  const bool finite = r.stress.allFinite() && r.tangent.allFinite() && std::isfinite(storedEnergy2D(m, p));
  const bool ok = r.converged() && finite;
  const Voigt stress = ok ? r.stress : m.stress(start);
  for (int i = 0; i < 3; ++i) {
    out.stress[i] = stress[i];
    for (int j = 0; j < 3; ++j) out.ddsdde[i + 3 * j] = ok ? r.tangent(i, j) : m.stiffness()(i, j);
  }
  if (!ok) return finite ? m.explain(r) : overflow(in);
  if (p.band) {
    const BandState& b = *p.band;
    writeBand(out.statev, true, Vec3(b.crackNormal[0], b.crackNormal[1], 0.0), Vec3(b.jump[0], b.jump[1], 0.0),
              fromInPlane(b.onsetStrain), b.integrity, b.volumeFraction);
  } else {
    out.statev[kDamage] = 0.0;  // an output: written whatever the caller set
  }
  out.statev[kDissipation] += r.dissipation;
  *out.sse = storedEnergy2D(m, p);
  *out.spd = out.statev[kDissipation];
  return "";
}

}  // namespace

void rotateBandState(double* s, const double* drot) {
  if (s[kCracked] != 1.0) return;
  Eigen::Matrix3d r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) r(i, j) = drot[i + 3 * j];  // Fortran DROT(i, j)
  if (r == Eigen::Matrix3d::Identity()) return;
  Eigen::Vector3d n(s[kNormal], s[kNormal + 1], s[kNormal + 2]), jump(s[kJump], s[kJump + 1], s[kJump + 2]);
  n = r * n, jump = r * jump;
  // eps_on as a tensor (half the engineering shears), ecm's order xx, yy, zz, yz, xz, xy.
  const double* e = s + kOnsetStrain;
  Eigen::Matrix3d t;
  t << e[0], 0.5 * e[5], 0.5 * e[4], 0.5 * e[5], e[1], 0.5 * e[3], 0.5 * e[4], 0.5 * e[3], e[2];
  t = r * t * r.transpose();
  const double onset[6] = {t(0, 0), t(1, 1), t(2, 2), 2.0 * t(1, 2), 2.0 * t(0, 2), 2.0 * t(0, 1)};
  for (int i = 0; i < 3; ++i) s[kNormal + i] = n[i], s[kJump + i] = jump[i];
  for (int i = 0; i < 6; ++i) s[kOnsetStrain + i] = onset[i];
}

MaterialParams materialFromProps(const double* props, int nprops, Hypothesis hypothesis) {
  MaterialParams p;
  p.name = "umat";
  p.model = enriched(props) ? ModelKind::Enriched : ModelKind::LinearElastic;
  p.elastic = {props[kYoungsModulus], props[kPoissonRatio], hypothesis};
  if (p.model == ModelKind::Enriched) {
    p.tensileStrength = props[kTensileStrength];
    p.softeningModulus = props[kSofteningModulus];
    p.softeningExponent = props[kSofteningExponent];
    p.bandWidth = props[kBandWidth];
  }
  (void)nprops;
  return p;
}

std::string propsProblem(const Inputs& in) {
  std::ostringstream msg;
  msg.precision(10);
  const bool shapeOk = (in.ndi == 3 && in.nshr == 3 && in.ntens == 6) || (in.ndi == 3 && in.nshr == 1 && in.ntens == 4) ||
                       (in.ndi == 2 && in.nshr == 1 && in.ntens == 3);
  if (!shapeOk) {
    msg << "NDI = " << in.ndi << ", NSHR = " << in.nshr << ", NTENS = " << in.ntens
        << ": supported are 3D solids (3, 3, 6), plane strain and axisymmetric (3, 1, 4) and plane stress (2, 1, 3)";
    return msg.str();
  }
  if (in.nprops < kMinProps || in.nprops > kPropCount) {
    msg << "NPROPS = " << in.nprops << ": ecm's UMAT takes " << kMinProps << " or " << kPropCount
        << " constants: model, E, nu, f_t', E_p, n, h, H, snap_back[, substep levels] (docs/fe-codes.md)";
    return msg.str();
  }
  if (in.nstatv < kStateCount) {
    msg << "NSTATV = " << in.nstatv << ": ecm's UMAT needs " << kStateCount << " state variables (*DEPVAR, "
        << kStateCount << "; docs/fe-codes.md)";
    return msg.str();
  }
  const double* p = in.props;
  const auto bad = [&](int i, const std::string& range) {
    msg << propName(i) << " = " << p[i] << ": " << range;
    return msg.str();
  };
  if (!isInteger(p[kModel], 0, 1)) return bad(kModel, "must be 1 (enriched) or 0 (linear elastic)");
  if (!isInteger(p[kSnapBack], 0, 1)) return bad(kSnapBack, "must be 0 (stop: PNEWDT < 1) or 1 (release)");
  if (in.nprops > kSubstepLevels && !isInteger(p[kSubstepLevels], 0, 20)) return bad(kSubstepLevels, "must be an integer in [0, 20]");
  if (!(p[kEffectiveSize] >= 0.0)) return bad(kEffectiveSize, "must be > 0, or 0 to take the caller's CELENT");
  try {
    materialFromProps(p, in.nprops, in.ntens == 3 ? Hypothesis::PlaneStress : Hypothesis::ThreeDimensional).validate();
  } catch (const ParameterError& e) {
    msg << "PROPS (model, E, nu, f_t', E_p, n, h, H, snap_back): " << e.what();
    return msg.str();
  }
  if (enriched(p)) {
    const double bigH = effectiveSizeOf(in);
    if (!(bigH > 0.0) || !std::isfinite(bigH)) {
      msg << "PROPS(8) H = 0 asks for the caller's CELENT, but it gave " << in.celent
          << " (CalculiX gives none): set H > 0 in PROPS(8)";
      return msg.str();
    }
    if (const std::string why = effectiveSizeProblem(bigH, p[kBandWidth]); !why.empty())
      return std::string(in.props[kEffectiveSize] > 0.0 ? "PROPS(8): " : "CELENT: ") + why;
  }
  return "";
}

std::string stateProblem(const Inputs& in, const double* statev) {
  std::ostringstream msg;
  msg.precision(10);
  const auto bad = [&](int i, const std::string& why) {
    msg << "STATEV(" << i + 1 << ") = " << statev[i] << ": " << why
        << " (set STATEV as docs/fe-codes.md says: 0, with STATEV(2) = 1)";
    return msg.str();
  };
  for (int i = 0; i < in.ntens; ++i)
    if (!std::isfinite(in.stran[i])) {
      msg << "STRAN(" << i + 1 << ") = " << in.stran[i] << ": the strain at the start of the increment is not a number";
      return msg.str();
    }
  for (int i = 0; i < kStateCount; ++i)
    if (!std::isfinite(statev[i])) return bad(i, "not a number");
  if (statev[kCracked] != 0.0 && statev[kCracked] != 1.0) return bad(kCracked, "must be 0 (intact) or 1 (cracked)");
  if (statev[kDissipation] < 0.0) return bad(kDissipation, "the dissipation so far is >= 0");
  if (statev[kCracked] == 0.0) return "";
  if (!(statev[kIntegrity] >= 0.0 && statev[kIntegrity] <= 1.0)) return bad(kIntegrity, "a cracked point's integrity is in [0, 1]");
  if (!(statev[kVolumeFraction] > 0.0 && statev[kVolumeFraction] < 1.0))
    return bad(kVolumeFraction, "a cracked point's f = h / H is in (0, 1)");
  const double length = std::hypot(statev[kNormal], statev[kNormal + 1], statev[kNormal + 2]);
  if (std::abs(length - 1.0) > 1e-6) return bad(kNormal, "a cracked point's normal (STATEV 3-5) is a unit vector");
  if (in.ntens == 3 && std::abs(statev[kNormal + 2]) > 1e-6)
    return bad(kNormal + 2, "plane stress: a cracked point's normal lies in the plane (STATEV(5) = 0)");
  return "";
}

std::string incrementProblem(const Inputs& in, bool& fatal) {
  std::ostringstream msg;
  msg.precision(10);
  fatal = false;
  for (int i = 0; i < in.ntens; ++i)
    if (!std::isfinite(in.dstran[i])) {
      msg << "DSTRAN(" << i + 1 << ") = " << in.dstran[i] << ": the strain increment is not a number";
      return msg.str();
    }
  if (!in.drot) return "";
  Eigen::Matrix3d r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) r(i, j) = in.drot[i + 3 * j];
  if (!r.allFinite()) return "DROT is not a number";
  const double off = (r.transpose() * r - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  if (off > 1e-6 || r.determinant() < 0.0) {
    fatal = true;
    msg << "DROT is not a rotation (|R^T R - I| = " << off << ", det R = " << r.determinant() << ")";
    return msg.str();
  }
  return "";
}

std::string update(const Inputs& in, const Outputs& out, bool& fatal) {
  fatal = true;
  if (std::string why = propsProblem(in); !why.empty()) return why;
  if (std::string why = stateProblem(in, out.statev); !why.empty()) return why;
  if (std::string why = incrementProblem(in, fatal); !why.empty()) return why;
  if (in.drot) rotateBandState(out.statev, in.drot);  // NLGEOM: the band turns with the material
  UpdateOptions options(in.props[kSnapBack] == 1.0 ? SnapBackPolicy::Release : SnapBackPolicy::Stop, true);
  options.substepLevels = in.nprops > kSubstepLevels ? static_cast<int>(in.props[kSubstepLevels]) : 10;
  const double bigH = enriched(in.props) ? effectiveSizeOf(in) : 1.0;
  if (in.ntens == 3) return updatePlaneStress(in, out, *materialFor(in, Hypothesis::PlaneStress).m2, options, bigH);
  return update3D(in, out, *materialFor(in, Hypothesis::ThreeDimensional).m3, options, bigH);
}

}  // namespace ecm::umat

extern "C" void umat_(double* stress, double* statev, double* ddsdde, double* sse, double* spd, double* /*scd*/,
                      double* /*rpl*/, double* /*ddsddt*/, double* /*drplde*/, double* /*drpldt*/, const double* stran,
                      const double* dstran, const double* /*time*/, const double* /*dtime*/, const double* /*temp*/,
                      const double* /*dtemp*/, const double* /*predef*/, const double* /*dpred*/, const char* /*cmname*/,
                      const int* ndi, const int* nshr, const int* ntens, const int* nstatv, const double* props,
                      const int* nprops, const double* /*coords*/, const double* drot, double* pnewdt,
                      const double* celent, const double* /*dfgrd0*/, const double* /*dfgrd1*/, const int* noel,
                      const int* npt, const int* /*layer*/, const int* /*kspt*/, const int* kstep,
                      const int* kinc, size_t /*cmname_len*/) {
  using namespace ecm::umat;
  const Inputs in{stran, dstran, *ndi, *nshr, *ntens, *nstatv, *nprops, props, celent ? *celent : 0.0, drot};
  const Outputs out{stress, statev, ddsdde, sse, spd, pnewdt};
  bool fatal = false;
  std::string why;
  try {
    why = update(in, out, fatal);
  } catch (const std::exception& e) {  // nothing may unwind into Fortran
    why = e.what();
    fatal = true;
  }
  if (fatal) {
    std::fprintf(stderr, "*ERROR in ecm umat (element %d, point %d): %s\n", noel ? *noel : 0, npt ? *npt : 0, why.c_str());
    std::exit(2);  // bad input: the analysis cannot go on (Abaqus's XIT is not available to a C library)
  }
  if (!why.empty()) {
    // A failed update: ask the caller for a smaller increment; the state stays at the start. A
    // PNEWDT of 0 or less is CalculiX's "no request" (docs/fe-codes.md): 0.5 replaces it.
    *pnewdt = *pnewdt > 0.0 ? std::min(*pnewdt, 0.5) : 0.5;
    std::fprintf(stderr, "*WARNING in ecm umat (element %d, point %d): %s; PNEWDT = %g\n", noel ? *noel : 0,
                 npt ? *npt : 0, why.c_str(), *pnewdt);
  }
  traceCall({kstep ? *kstep : 0, kinc ? *kinc : 0, noel ? *noel : 0, npt ? *npt : 0, *ntens, *nstatv, stran, dstran, stress,
             statev, *sse, *spd, *pnewdt});
}
