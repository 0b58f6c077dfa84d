#include "driver/umat_driver.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "driver/mixed_increment_3d.hpp"
#include "driver/row_check.hpp"
#include "umat/umat_props.hpp"

namespace ecm::driver {

namespace {

constexpr int kAbaqusToEcm[6] = {0, 1, 2, 5, 4, 3};  // 11, 22, 33, 12, 13, 23 -> xx, yy, zz, xy, xz, yz

std::vector<double> toAbaqus(const Voigt6& v) {
  std::vector<double> a(6);
  for (int i = 0; i < 6; ++i) a[i] = v[kAbaqusToEcm[i]];
  return a;
}

Voigt6 fromAbaqus(const std::vector<double>& a) {
  Voigt6 v;
  for (int i = 0; i < 6; ++i) v[kAbaqusToEcm[i]] = a[i];
  return v;
}

Tangent6 tangentFromAbaqus(const std::vector<double>& ddsdde) {
  Tangent6 k;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) k(kAbaqusToEcm[i], kAbaqusToEcm[j]) = ddsdde[i + 6 * j];
  return k;
}

// F = I + eps (small strain; the UMATs that read DFGRD get a consistent one), column-major.
void deformationGradient(const Voigt6& e, double* f) {
  Voigt6 half = e;
  half.tail<3>() *= 0.5;  // tensor shears
  const Eigen::Matrix3d t = Eigen::Matrix3d::Identity() + stressTensor(half);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) f[i + 3 * j] = t(i, j);
}

bool allFinite(const std::vector<double>& v) {
  return std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); });
}

// The committed state of the point between increments.
struct State {
  Voigt6 strain = Voigt6::Zero(), stress = Voigt6::Zero();
  std::vector<double> statev;
  double sse = 0.0, spd = 0.0, scd = 0.0;
  Tangent6 tangent = Tangent6::Zero();  // DDSDDE of the last converged call: the next predictor
};

// Where a call sits in the run (TIME, DTIME, KSTEP, KINC).
struct Clock {
  double stepTime = 0.0, totalTime = 0.0, dtime = 1.0;
  int kstep = 1, kinc = 1;
};

struct Trial {
  UmatCall call;
  std::string why;  // "" when the call gave a usable answer
};

Trial callFrom(const UmatLibrary& lib, const UmatScene& scene, const State& from, const Voigt6& d, const Clock& clock) {
  Trial t;
  UmatCall& c = t.call;
  c.stress = toAbaqus(from.stress);
  c.statev = from.statev;
  c.sse = from.sse, c.spd = from.spd, c.scd = from.scd;
  c.stran = toAbaqus(from.strain);
  c.dstran = toAbaqus(d);
  c.time[0] = clock.stepTime, c.time[1] = clock.totalTime;
  c.dtime = clock.dtime;
  c.kstep = clock.kstep, c.kinc = clock.kinc;
  c.celent = scene.characteristicLength;
  deformationGradient(from.strain, c.dfgrd0);
  deformationGradient(from.strain + d, c.dfgrd1);
  lib.call(c, scene.props, scene.materialName);
  std::ostringstream why;
  why.precision(6);
  if (c.pnewdt < 1.0) why << "the UMAT asked for a smaller increment (PNEWDT = " << c.pnewdt << ")";
  else if (!allFinite(c.stress)) why << "the UMAT returned a STRESS that is not a number";
  else if (!allFinite(c.ddsdde)) why << "the UMAT returned a DDSDDE that is not a number";
  else if (!allFinite(c.statev)) why << "the UMAT returned a STATEV that is not a number";
  else if (!std::isfinite(c.sse) || !std::isfinite(c.spd) || !std::isfinite(c.scd))
    why << "the UMAT returned an energy (SSE, SPD, SCD) that is not a number";
  t.why = why.str();
  return t;
}

struct Piece {
  State end;
  Voigt6 increment = Voigt6::Zero();
  int iterations = 0;
  std::string why;  // "" on success
};

// One piece of an increment under mixed control: Newton on the stress-controlled strains with
// the UMAT's DDSDDE, each iteration a call from the committed start (a UMAT keeps nothing).
Piece piece(const UmatLibrary& lib, const UmatScene& scene, const State& from, const Segment3& s,
            const Voigt6& strainIncrement, const Voigt6& stressTarget, const Clock& clock, const Tangent6& elastic) {
  Piece out;
  const unsigned mask = stressMask(s.control);
  Voigt6 d = mixedIncrement(from.tangent, from.stress, s.control, strainIncrement, stressTarget);
  if (!d.allFinite()) d = mixedIncrement(elastic, from.stress, s.control, strainIncrement, stressTarget);
  double residualNorm = INFINITY;
  for (int it = 0; it < 100; ++it) {
    out.iterations = it + 1;
    Trial t = callFrom(lib, scene, from, d, clock);
    if (!t.why.empty()) {
      out.why = t.why;
      return out;
    }
    const Voigt6 stress = fromAbaqus(t.call.stress);
    const Tangent6 tangent = tangentFromAbaqus(t.call.ddsdde);
    Voigt6 residual = Voigt6::Zero();
    for (int i = 0; i < 6; ++i)
      if (mask & (1u << i)) residual[i] = stress[i] - stressTarget[i];
    residualNorm = residual.norm();
    if (residualNorm <= scene.stressTolerance) {
      out.end = {from.strain + d, stress, std::move(t.call.statev), t.call.sse, t.call.spd, t.call.scd, tangent};
      out.increment = d;
      return out;
    }
    const Voigt6 correction = mixedIncrement(tangent, stress, s.control, Voigt6::Zero(), stressTarget);
    if (!correction.allFinite()) {
      out.why = "the stress-controlled block of DDSDDE is singular";
      return out;
    }
    d += correction;
  }
  std::ostringstream msg;
  msg << "stress control did not converge in 100 iterations (residual " << residualNorm << " MPa, tolerance "
      << scene.stressTolerance << " MPa)";
  out.why = msg.str();
  return out;
}

UmatRow rowOf(const State& p, int increment, int segment) {
  UmatRow r;
  r.increment = increment;
  r.segment = segment;
  r.strain = p.strain;
  r.stress = p.stress;
  r.state = p.statev;
  r.sse = p.sse, r.spd = p.spd, r.scd = p.scd;
  return r;
}

bool allNumbers(const UmatRow& r) {
  return r.strain.allFinite() && r.stress.allFinite() && allFinite(r.state) && std::isfinite(r.work);
}

}  // namespace

UmatScene umatSceneFor(const PointScene3& scene) {
  UmatScene u;
  u.name = scene.name;
  // PROPS 1-9: the UMAT's own sub-steps keep their default; the driver halves increments itself.
  u.props = umat::propsFor(scene.material, scene.material.model == ModelKind::Enriched ? scene.effectiveSize : 0.0,
                           scene.snapBack);
  u.initialState.assign(17, 0.0);  // umat/umat_layout.hpp: kStateCount, STATEV(2) = 1
  u.initialState[1] = 1.0;
  u.characteristicLength = scene.effectiveSize;
  u.materialName = "ECM";
  u.path = scene.path;
  u.stressTolerance = scene.relativeTolerance *
                      (scene.material.model == ModelKind::LinearElastic ? 1.0 : scene.material.tensileStrength);
  u.substepLevels = scene.substepLevels;
  u.propsSource = "material '" + scene.material.name + "' in ecm's PROPS layout";
  return u;
}

UmatRun runUmat(const UmatScene& scene, const UmatLibrary& lib, const UmatObserver& observe) {
  UmatRun run;
  State p;
  p.statev = scene.initialState;
  int total = 0;
  for (const Segment3& s : scene.path) total += s.increments;
  // The predictor of the first increment: the UMAT's DDSDDE for a null increment (not committed).
  {
    Clock clock;
    clock.dtime = scene.path.empty() ? 1.0 : 1.0 / scene.path.front().increments;
    Trial t = callFrom(lib, scene, p, Voigt6::Zero(), clock);
    if (!t.why.empty()) {
      run.failure = "the call with a null increment at the start: " + t.why;
      return run;
    }
    p.tangent = tangentFromAbaqus(t.call.ddsdde);
  }
  const Tangent6 elastic = p.tangent;
  double work = 0.0;
  int increment = 0;
  UmatRow first = rowOf(p, 0, 0);
  run.history.push_back(first);
  if (observe) observe(first, 0, total);
  for (std::size_t seg = 0; seg < scene.path.size(); ++seg) {
    const Segment3& s = scene.path[seg];
    const Voigt6 startStrain = p.strain, startStress = p.stress;
    for (int k = 1; k <= s.increments; ++k) {
      ++increment;
      const double t = double(k) / s.increments;
      const Voigt6 strainTarget = startStrain + t * (s.target - startStrain);
      const Voigt6 stressTarget = startStress + t * (s.target - startStress);
      std::string why;
      bool done = false;
      for (int level = 0; level <= scene.substepLevels && !done; ++level) {
        const int pieces = 1 << level;
        State q = p;
        double w = work;
        int iterations = 0;
        bool ok = true;
        for (int i = 1; i <= pieces && ok; ++i) {
          const double f = double(i) / pieces;
          const Voigt6 eTarget = p.strain + f * (strainTarget - p.strain);
          const Voigt6 sTarget = p.stress + f * (stressTarget - p.stress);
          Clock clock;
          clock.dtime = 1.0 / (double(s.increments) * pieces);
          clock.stepTime = (k - 1) / double(s.increments) + (i - 1) * clock.dtime;
          clock.totalTime = double(seg) + clock.stepTime;
          clock.kstep = static_cast<int>(seg) + 1;
          clock.kinc = k;
          Piece r = piece(lib, scene, q, s, eTarget - q.strain, sTarget, clock, elastic);
          iterations += r.iterations;
          if (!r.why.empty()) {
            ok = false;
            why = r.why;
            break;
          }
          w += 0.5 * (q.stress + r.end.stress).dot(r.increment);
          q = std::move(r.end);
        }
        if (!ok) continue;
        p = std::move(q);
        work = w;
        UmatRow row = rowOf(p, increment, static_cast<int>(seg) + 1);
        row.work = work;
        row.iterations = iterations;
        row.substeps = pieces;
        if (!allNumbers(row)) {
          run.failure = notANumberFailure(increment, row.segment);
          return run;
        }
        run.history.push_back(row);
        if (observe) observe(row, increment, total);
        done = true;
      }
      if (!done) {
        std::ostringstream msg;
        msg << "increment " << increment << " (segment " << seg + 1 << ") did not converge in "
            << (1 << scene.substepLevels) << " pieces: " << why;
        run.failure = msg.str();
        return run;
      }
    }
  }
  run.completed = true;
  return run;
}

}  // namespace ecm::driver
