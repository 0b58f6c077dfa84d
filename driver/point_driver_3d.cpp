#include "driver/point_driver_3d.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "driver/golden_maximum.hpp"
#include "driver/mixed_increment_3d.hpp"
#include "driver/row_check.hpp"

namespace ecm::driver {

namespace {

struct Step {
  UpdateResult3 result;
  Voigt6 increment = Voigt6::Zero();
  int iterations = 0;
  bool ok = false;
};

// One mixed-control increment from `point` (committed on success).
Step mixedStep(const Material3D& m, MaterialPoint3& point, const Voigt6& current, const std::array<Control, 6>& control,
               const Voigt6& strainIncrement, const Voigt6& stressTarget, const EffectiveSize3& size,
               const UpdateOptions& options, double tol) {
  Step out;
  Voigt6 d = mixedIncrement(m.stiffness(), current, control, strainIncrement, stressTarget);
  const unsigned mask = stressMask(control);
  for (int it = 0; it < 100; ++it) {
    MaterialPoint3 trial = point;
    out.result = m.update(trial, d, size, options);
    out.iterations = it + 1;
    if (!out.result.converged()) return out;
    Voigt6 residual = Voigt6::Zero();
    for (int i = 0; i < 6; ++i)
      if (mask & (1u << i)) residual[i] = out.result.stress[i] - stressTarget[i];
    if (residual.norm() <= tol) {
      point = trial;
      out.increment = d;
      out.ok = true;
      return out;
    }
    const Voigt6 correction = mixedIncrement(out.result.tangent, out.result.stress, control, Voigt6::Zero(), stressTarget);
    if (!correction.allFinite()) return out;
    d += correction;
  }
  out.result.status = UpdateStatus::NotConverged;
  return out;
}

HistoryRow3 rowOf(const Material3D& m, const MaterialPoint3& p, const Voigt6& stress, int increment, int segment) {
  HistoryRow3 r;
  r.increment = increment;
  r.segment = segment;
  r.strain = p.strain;
  r.stress = stress;
  r.storedEnergy = m.storedEnergy(p);
  if (p.band) {
    r.damage = p.band->damage();
    r.integrity = p.band->integrity;
    r.crackNormal = p.band->crackNormal;
    r.normalJump = p.band->normalJump();
    r.slidingJump = p.band->slidingJump().norm();
    r.volumeFraction = p.band->volumeFraction;
  }
  return r;
}

// The largest principal stress (MPa).
double firstPrincipal(const Voigt6& s) { return largestPrincipal(s).first; }

// The fraction a in (0, 1) of a piece where stressAt(a) has a maximum above `ends` (the larger of
// its ends' stresses), or nullopt: samples evenly spaced and geometrically closer to the start
// (where a softening band's maximum lies), then golden section next to the best, as in 2D.
template <class F>
std::optional<double> maximumInside(const F& stressAt, double ends) {
  std::vector<double> as;
  for (int k = 1; k < 16; ++k) as.push_back(k / 16.0);
  for (double x = 1e-6; x < 1.0 / 16.0; x *= 2.0) as.push_back(x);
  std::sort(as.begin(), as.end());
  as.insert(as.begin(), 0.0);
  as.push_back(1.0);
  std::size_t top = 0;
  double topStress = -INFINITY;
  for (std::size_t k = 1; k + 1 < as.size(); ++k)
    if (const double sk = stressAt(as[k]); sk > topStress) topStress = sk, top = k;
  if (!(topStress > ends)) return std::nullopt;
  const double a = goldenMaximum(stressAt, as[top - 1], as[top + 1], 1e-12);
  if (!(stressAt(a) > ends)) return std::nullopt;
  return a;
}

}  // namespace

int totalIncrements(const PointScene3& scene) {
  int n = 0;
  for (const Segment3& s : scene.path) n += s.increments;
  return n;
}

PointRun3 runPoint3D(const PointScene3& scene, const RowObserver3& observe) {
  const Material3D m(scene.material);
  const auto size = EffectiveSize3::fixed(scene.effectiveSize);
  const double tol = scene.relativeTolerance * (scene.material.model == ModelKind::LinearElastic ? 1.0 : scene.material.tensileStrength);
  PointRun3 run;
  MaterialPoint3 p;
  Voigt6 stress = Voigt6::Zero();
  double work = 0.0, dissipation = 0.0;
  double peakSoFar = 0.0;  // the largest principal stress of the rows so far (MPa)
  int increment = 0;
  const int total = totalIncrements(scene);
  run.history.push_back(rowOf(m, p, stress, 0, 0));
  // A row that is not all numbers ends the run with its increment named (the rows before it stay).
  const auto record = [&](HistoryRow3 row) {
    row.work = work;
    row.dissipation = dissipation;
    if (!isAllNumbers(row)) {
      run.failure = notANumberFailure(increment, row.segment);
      return false;
    }
    run.history.push_back(row);
    if (observe) observe(row, increment, total);
    return true;
  };
  for (std::size_t seg = 0; seg < scene.path.size(); ++seg) {
    const Segment3& s = scene.path[seg];
    // Strain targets are absolute at the segment's end: per-increment strain steps from where it starts.
    const Voigt6 startStrain = p.strain, startStress = stress;
    for (int k = 1; k <= s.increments; ++k) {
      ++increment;
      const double t = double(k) / s.increments;
      Voigt6 strainTarget = startStrain + t * (s.target - startStrain);
      Voigt6 stressTarget = startStress + t * (s.target - startStress);
      // Pieces: 1, 2, 4, ... of this increment until each converges.
      bool done = false;
      std::string why;
      for (int level = 0; level <= scene.substepLevels && !done; ++level) {
        const int pieces = 1 << level;
        MaterialPoint3 q = p;
        Voigt6 qs = stress;
        double w = work, diss = dissipation;
        std::vector<HistoryRow3> onsetRows;
        bool ok = true, released = false;
        int iterations = 0;
        const Voigt6 fromStrain = p.strain, fromStress = stress;
        for (int i = 1; i <= pieces && ok; ++i) {
          const double f = double(i) / pieces;
          const Voigt6 eTarget = fromStrain + f * (strainTarget - fromStrain), sTarget = fromStress + f * (stressTarget - fromStress);
          UpdateOptions options(scene.snapBack, true);
          options.stressControlled = stressMask(s.control);
          options.substepLevels = 0;
          // An intact enriched point steps exactly to onset first (the elastic increment is exact).
          if (!q.band && m.enriched()) {
            const Voigt6 elastic = mixedIncrement(m.stiffness(), qs, s.control, eTarget - q.strain, sTarget);
            if (const auto alpha = m.enriched()->onsetFraction(q.strain, elastic); alpha && *alpha > 0.0 && *alpha < 1.0) {
              const Voigt6 before = qs;
              Step o = mixedStep(m, q, qs, s.control, *alpha * (eTarget - q.strain), qs + *alpha * (sTarget - qs), size, options, tol);
              if (!o.ok) { ok = false; why = m.explain(o.result); break; }
              w += 0.5 * (before + o.result.stress).dot(o.increment);
              qs = o.result.stress;
              HistoryRow3 row = rowOf(m, q, qs, increment, static_cast<int>(seg) + 1);
              row.onset = true;
              row.work = w;
              row.dissipation = diss;
              onsetRows.push_back(row);
            }
          }
          const Voigt6 before = qs;
          const MaterialPoint3 from = q;
          Step o = mixedStep(m, q, qs, s.control, eTarget - q.strain, sTarget, size, options, tol);
          if (!o.ok) { ok = false; why = m.explain(o.result); break; }
          // A maximum of the largest principal stress inside the piece, above every stress of the
          // run so far, gets a row of its own, as in 2D (docs/inputs.md): the peak of a point
          // whose stress rises after onset lies between rows. (A piece that ends cracked: its start
          // may be a hair below onset, where the step to onset left it.)
          if (q.band) {
            const auto stateAt = [&](double a, MaterialPoint3& at) {
              at = from;
              return mixedStep(m, at, before, s.control, a * (eTarget - from.strain), before + a * (sTarget - before), size, options, tol);
            };
            const auto stressAt = [&](double a) {
              MaterialPoint3 at;
              const Step r = stateAt(a, at);
              return r.ok ? firstPrincipal(r.result.stress) : -INFINITY;
            };
            if (const std::optional<double> a = maximumInside(stressAt, std::max(firstPrincipal(before), firstPrincipal(o.result.stress)));
                a && stressAt(*a) > peakSoFar) {
              MaterialPoint3 at;
              const Step r = stateAt(*a, at);
              HistoryRow3 row = rowOf(m, at, r.result.stress, increment, static_cast<int>(seg) + 1);
              row.work = w + 0.5 * (before + r.result.stress).dot(r.increment);
              row.dissipation = diss + r.result.dissipation;
              onsetRows.push_back(row);
            }
          }
          iterations += o.iterations;
          w += 0.5 * (before + o.result.stress).dot(o.increment);
          diss += o.result.dissipation;
          qs = o.result.stress;
          released = released || o.result.released;
        }
        if (!ok) continue;
        for (HistoryRow3& r : onsetRows) {
          peakSoFar = std::max(peakSoFar, firstPrincipal(r.stress));
          run.history.push_back(r);
        }
        p = q;
        stress = qs;
        work = w;
        dissipation = diss;
        peakSoFar = std::max(peakSoFar, firstPrincipal(stress));
        HistoryRow3 row = rowOf(m, p, stress, increment, static_cast<int>(seg) + 1);
        row.iterations = iterations;
        row.substeps = pieces;
        row.snapBackRelease = released;
        if (!record(row)) return run;
        done = true;
      }
      if (!done) {
        std::ostringstream msg;
        msg << "increment " << increment << " did not converge in " << (1 << scene.substepLevels) << " pieces: " << why;
        run.failure = msg.str();
        return run;
      }
    }
  }
  run.completed = true;
  return run;
}

std::vector<Segment3> presetSegments3(const std::string& name, double strain, int increments, double confinement,
                                      const Vec3& direction) {
  Segment3 s;
  s.increments = increments;
  if (name == "uniaxial_tension") {
    for (int i = 1; i < 6; ++i) s.control[i] = Control::Stress;
    s.target[0] = strain;
    return {s};
  }
  if (name == "triaxial") {
    // First the confinement (elastic), then eps_xx at constant lateral stress.
    Segment3 c;
    c.increments = std::max(1, increments / 10);
    for (int i = 0; i < 6; ++i) c.control[i] = Control::Stress;
    c.target[1] = c.target[2] = confinement;
    for (int i = 1; i < 6; ++i) s.control[i] = Control::Stress;
    s.target[0] = strain;
    s.target[1] = s.target[2] = confinement;
    return {c, s};
  }
  // rotated_axis: uniaxial strain e d (x) d, every component strain-controlled.
  const Vec3 d = direction.normalized();
  s.target = stressVoigt(strain * d * d.transpose());
  s.target.tail<3>() *= 2.0;
  return {s};
}

}  // namespace ecm::driver
