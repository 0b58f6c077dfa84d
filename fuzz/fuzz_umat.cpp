// Fuzz harness: the UMAT entry (umat/umat_layout.hpp's update(), what umat_() calls) as a finite
// element code could call it: NDI/NSHR/NTENS, PROPS, NSTATV and STATEV, CELENT, a sequence of
// strain increments with rotations (DROT), committed or only tried as a global Newton does. Each
// value is either plausible or adversarial (NaN, infinities, zero, negative, huge, tiny).
// Contract checked at every call:
// - nothing escapes but a returned reason: no crash, no sanitizer report, no exception;
// - a refused call (fatal, or a failed update) names its reason;
// - a converged update of finite inputs gives a finite STRESS, DDSDDE, SSE, SPD and STATEV, a
//   damage in [0, 1] that did not fall and a dissipation that did not fall;
// - a failed update leaves STRESS finite when the start state was.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <string>
#include <vector>

#include "umat/umat_layout.hpp"

namespace {

using namespace ecm::umat;

struct Bytes {
  const std::uint8_t* data;
  std::size_t size, pos = 0;
  unsigned byte() { return pos < size ? data[pos++] : 0u; }
  double unit() { return ((byte() << 8) | byte()) / 65535.0; }  // in [0, 1]
  double logRange(double lo, double hi) { return lo * std::pow(hi / lo, unit()); }
  bool more() const { return pos < size; }
  // A plausible value in [lo, hi] (log scale when lo > 0) 7 times in 8, else an adversarial one.
  double value(double lo, double hi) {
    const unsigned kind = byte() % 32;
    if (kind < 28) return lo > 0.0 ? logRange(lo, hi) : lo + (hi - lo) * unit();
    return adversarial();
  }
  double adversarial() {
    constexpr double inf = std::numeric_limits<double>::infinity();
    const double special[] = {std::numeric_limits<double>::quiet_NaN(), inf, -inf, 0.0, -1.0, 1e300, -1e300, 1e-300,
                              std::numeric_limits<double>::denorm_min(), std::numeric_limits<double>::max(), 0.5, 2.0};
    return special[byte() % (sizeof(special) / sizeof(double))];
  }
};

// What the broken call saw, printed with the report.
struct Seen {
  int ntens = 0, nprops = 0;
  const double *props = nullptr, *stran = nullptr, *dstran = nullptr, *statev = nullptr, *stress = nullptr, *ddsdde = nullptr,
               *statevOut = nullptr;
} seen;

void print(const char* name, const double* v, int n) {
  std::fprintf(stderr, "  %s:", name);
  for (int i = 0; v && i < n; ++i) std::fprintf(stderr, " %.17g", v[i]);
  std::fprintf(stderr, "\n");
}

// The inputs of call `call` (FUZZ_UMAT_VERBOSE: of every call).
void printInputs(int call) {
  std::fprintf(stderr, "call %d\n", call);
  print("PROPS", seen.props, seen.nprops);
  print("STRAN", seen.stran, seen.ntens);
  print("DSTRAN", seen.dstran, seen.ntens);
  print("STATEV in", seen.statev, kStateCount);
}

[[noreturn]] void broken(const char* what, int call, const std::string& why) {
  std::fprintf(stderr, "UMAT contract broken: %s (%s)\n", what, why.c_str());
  printInputs(call);
  print("STATEV out", seen.statevOut, kStateCount);
  print("STRESS out", seen.stress, seen.ntens);
  print("DDSDDE out", seen.ddsdde, seen.ntens * seen.ntens);
  std::abort();
}

bool finite(const std::vector<double>& v, std::size_t n) {
  for (std::size_t i = 0; i < n && i < v.size(); ++i)
    if (!std::isfinite(v[i])) return false;
  return true;
}

// A rotation from four bytes' quaternion, or (adversarial) a matrix that is not one.
void rotation(Bytes& b, double* r) {
  const unsigned kind = b.byte() % 8;
  if (kind >= 6) {
    for (int i = 0; i < 9; ++i) r[i] = b.value(-1.0, 1.0);
    return;
  }
  double q[4];
  double norm = 0.0;
  for (double& c : q) c = 2.0 * b.unit() - 1.0, norm += c * c;
  if (kind < 2 || norm < 1e-12) {
    for (int i = 0; i < 9; ++i) r[i] = i % 4 == 0 ? 1.0 : 0.0;
    return;
  }
  norm = std::sqrt(norm);
  const double w = q[0] / norm, x = q[1] / norm, y = q[2] / norm, z = q[3] / norm;
  const double m[9] = {1 - 2 * (y * y + z * z), 2 * (x * y + w * z),     2 * (x * z - w * y),
                       2 * (x * y - w * z),     1 - 2 * (x * x + z * z), 2 * (y * z + w * x),
                       2 * (x * z + w * y),     2 * (y * z - w * x),     1 - 2 * (x * x + y * y)};
  for (int i = 0; i < 9; ++i) r[i] = m[i];  // column-major, as DROT
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  Bytes b{data, size};
  // The element: 3D solid, plane strain or plane stress; 1 in 16 an arbitrary NDI/NSHR/NTENS.
  int ndi = 3, nshr = 3, ntens = 6;
  const unsigned layout = b.byte() % 16;
  if (layout < 5) ndi = 3, nshr = 1, ntens = 4;
  else if (layout < 10) ndi = 2, nshr = 1, ntens = 3;
  else if (layout == 15) ndi = static_cast<int>(b.byte() % 5), nshr = static_cast<int>(b.byte() % 5), ntens = ndi + nshr;
  if (ntens < 1 || ntens > 6) return 0;  // an FE code's NTENS is 1-6; arrays are sized by it

  // PROPS: model, E, nu, f_t', E_p, n, h, H, snap_back, substep levels.
  int nprops = b.byte() % 8 == 0 ? static_cast<int>(b.byte() % 12) : 9 + static_cast<int>(b.byte() % 2);
  std::vector<double> props(12, 0.0);
  props[kModel] = b.byte() % 8 == 0 ? b.adversarial() : (b.byte() % 4 == 0 ? 0.0 : 1.0);
  props[kYoungsModulus] = b.value(1.0, 1e6);
  props[kPoissonRatio] = b.value(-0.99, 0.49);
  props[kTensileStrength] = b.value(1e-3, 1e3);
  props[kSofteningModulus] = b.value(1e-3, 1e6);
  props[kSofteningExponent] = b.value(0.001, 0.499);
  props[kBandWidth] = b.value(1e-4, 10.0);
  props[kEffectiveSize] = b.byte() % 4 == 0 ? 0.0 : props[kBandWidth] * b.value(1.0, 1e6);
  props[kSnapBack] = b.byte() % 8 == 0 ? b.adversarial() : static_cast<double>(b.byte() % 2);
  // Sub-step levels up to 10 (the default; the UMAT takes 20): 2^16 sub-steps of an extreme law
  // took 10 s under ASan, by request, and more levels only repeat the same code.
  props[kSubstepLevels] = b.byte() % 8 == 0 ? b.adversarial() : static_cast<double>(b.byte() % 11);
  const double celent = b.value(1e-3, 1e3);

  // STATEV: fresh (0, integrity 1) or, 1 in 8, entries an initial condition could set.
  const int nstatv = b.byte() % 16 == 0 ? static_cast<int>(b.byte() % (kStateCount + 1)) : kStateCount + static_cast<int>(b.byte() % 3);
  std::vector<double> statev(std::max(nstatv, 1), 0.0), stress(ntens, 0.0), stran(ntens, 0.0), ddsdde(ntens * ntens, 0.0);
  if (nstatv > kIntegrity) statev[kIntegrity] = 1.0;
  if (b.byte() % 8 == 0)
    for (int k = 0, count = 1 + static_cast<int>(b.byte() % 6); k < count; ++k)
      statev[b.byte() % statev.size()] = b.byte() % 2 ? b.adversarial() : b.value(-1.0, 1.0);
  double sse = 0.0, spd = 0.0, pnewdt = 1.0;

  for (int call = 0; call < 48 && b.more(); ++call) {
    std::vector<double> dstran(ntens);
    const double scale = b.logRange(1e-9, 1e-1);
    for (double& d : dstran) d = b.byte() % 64 == 0 ? b.adversarial() : scale * (2.0 * b.unit() - 1.0);
    double drot[9];
    rotation(b, drot);
    const bool withRotation = b.byte() % 2 == 0;

    std::vector<double> tStress = stress, tStatev = statev, tDdsdde = ddsdde;
    double tSse = sse, tSpd = spd, tPnewdt = pnewdt;
    const Inputs in{stran.data(), dstran.data(), ndi, nshr, ntens, nstatv, nprops, props.data(), celent,
                    withRotation ? drot : nullptr};
    const Outputs out{tStress.data(), tStatev.data(), tDdsdde.data(), &tSse, &tSpd, &tPnewdt};
    seen = {ntens, nprops, props.data(), stran.data(), dstran.data(), statev.data(), tStress.data(), tDdsdde.data(), tStatev.data()};
    if (std::getenv("FUZZ_UMAT_VERBOSE")) printInputs(call);
    bool fatal = false;
    std::string why;
    try {
      why = update(in, out, fatal);
    } catch (const std::exception& e) {
      broken("an exception escaped update()", call, e.what());
    }
    if (fatal) {
      if (why.empty()) broken("fatal without a reason", call, why);
      return 0;  // the analysis stops here
    }
    const bool finiteInputs = finite(stran, ntens) && finite(dstran, ntens) && finite(statev, kStateCount) &&
                              (!withRotation || finite(std::vector<double>(drot, drot + 9), 9));
    if (!why.empty()) {
      if (finiteInputs && finite(stress, ntens) && !finite(tStress, ntens)) broken("failed update with a non-finite stress", call, why);
      continue;  // the caller cuts the increment: nothing is committed
    }
    if (!finiteInputs) broken("non-finite inputs accepted", call, why);
    if (!finite(tStress, ntens) || !finite(tDdsdde, ntens * ntens) || !finite(tStatev, kStateCount) || !std::isfinite(tSse) ||
        !std::isfinite(tSpd))
      broken("non-finite output of a converged update", call, why);
    if (props[kModel] == 1.0) {
      if (tStatev[kDamage] < 0.0 || tStatev[kDamage] > 1.0) broken("damage outside [0, 1]", call, why);
      if (statev[kCracked] == 1.0 && tStatev[kIntegrity] > statev[kIntegrity]) broken("damage fell", call, why);
      if (tStatev[kDissipation] < statev[kDissipation] - 1e-12 * std::abs(statev[kDissipation])) broken("dissipation fell", call, why);
    }
    if (b.byte() % 4 != 0) {  // converged: commit, as the FE code does
      stress = tStress, statev = tStatev, ddsdde = tDdsdde, sse = tSse, spd = tSpd;
      for (int i = 0; i < ntens; ++i) stran[i] += dstran[i];
    }
  }
  return 0;
}
