#include "driver/point_driver.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "driver/golden_maximum.hpp"
#include "driver/opening_control.hpp"
#include "driver/row_check.hpp"
#include "io/value_error.hpp"

namespace ecm::driver {

namespace {

// n . e . n for a Voigt strain (engineering shear).
double normalComponent(const Voigt& e, const Vec2& n) {
  return n[0] * n[0] * e[0] + n[1] * n[1] * e[1] + n[0] * n[1] * e[2];
}

double firstPrincipalStrain(const Voigt& e) { return principalStresses(Voigt(e[0], e[1], 0.5 * e[2])).first; }

class Runner {
 public:
  Runner(const PointScene& s, const RowObserver& o)
      : scene_(s), observe_(o), material_(s.material), size_(EffectiveSize::fixed(s.effectiveSize)) {
    const double ft = s.material.tensileStrength > 0.0 ? s.material.tensileStrength : 1.0;
    settings_.tolerance = s.relativeTolerance * ft;
    settings_.maxSubstepLevels = s.substepLevels;
    total_ = totalIncrements(s);
  }

  PointRun run() {
    try {
      record(0, 0, StepOutcome{}, false, false);
      for (int k = 0; k < static_cast<int>(scene_.path.size()); ++k) {
        const Segment& seg = scene_.path[k];
        const bool ok = seg.openingControl ? openingSegment(k, seg) : strainSegment(k, seg);
        if (!ok) return std::move(run_);
      }
    } catch (const NonFiniteRow& e) {
      run_.failure = e.what;
      return std::move(run_);
    }
    run_.completed = true;
    return std::move(run_);
  }

 private:
  bool strainSegment(int k, const Segment& seg) {
    const Voigt strain0 = point_.strain, stress0 = stress_;
    for (int i = 1; i <= seg.increments; ++i) {
      const double s = static_cast<double>(i) / seg.increments;
      MixedTarget t;
      t.control = seg.control;
      const auto aim = [&] {
        for (int c = 0; c < 3; ++c) {
          if (seg.control[c] == Control::Strain) t.strainIncrement[c] = strain0[c] + s * (seg.target[c] - strain0[c]) - point_.strain[c];
          else t.stress[c] = stress0[c] + s * (seg.target[c] - stress0[c]);
        }
      };
      aim();
      if (!stepToOnsetInside(k, t)) return false;
      aim();  // the rest of the increment, from the onset state
      const MaterialPoint start = point_;
      const StepOutcome out = mixedControlStep(material_, point_, stress_, t, size_, settings_, SnapBackPolicy::Stop);
      if (out.result.status == UpdateStatus::SnapBack) {
        if (!snapBack(k, t)) return false;
        continue;
      }
      if (!out.converged()) return fail(out, k, i);
      if (peakInside(k, t, start, out)) continue;
      record(k, ++increment_, out, false, false);
    }
    return true;
  }

  struct BranchState {
    OpeningOutcome out;
    MaterialPoint point;
  };
  // The maximum of the first principal stress on the branch traced under opening control from
  // `from` (stress `first`) to the normal jump `to` (stress `last`), if it lies strictly inside:
  // the stress rises at the start, and a sample inside is above both ends.
  std::optional<BranchState> stressMaximum(OpeningTarget o, const MaterialPoint& from, double first, double to,
                                           double last, double maxLoadFactor) const {
    const TwoPhasePoint* model = material_.enriched();
    const double j0 = from.band->normalJump();
    if (!(to > j0)) return std::nullopt;
    BranchState best;
    const auto stressAt = [&](double jump, bool keep) -> double {
      MaterialPoint m = from;
      o.normalJump = jump;
      const OpeningOutcome r = openingControlStep(*model, m, o, settings_.tolerance);
      if (!r.step.converged() || r.loadFactor < 0.0 || r.loadFactor > maxLoadFactor) return -INFINITY;
      if (keep) best = {r, m};
      return principalStresses(r.step.result.stress).first;
    };
    // Only a branch whose stress rises at the start can have a maximum inside (one solve).
    const double d = std::min(1e-3 * (to - j0), 1e-6 * model->bandWidth());
    if (!(stressAt(j0 + d, false) > first)) return std::nullopt;
    // Bracket the maximum among samples, evenly spaced and geometrically closer to the start
    // (where a softening band's maximum lies), then golden section next to the best sample.
    std::vector<double> js;
    for (int k = 1; k < 16; ++k) js.push_back(j0 + (to - j0) * k / 16.0);
    for (double x = d; x < (to - j0) / 16.0; x *= 2.0) js.push_back(j0 + x);
    std::sort(js.begin(), js.end());
    js.insert(js.begin(), j0);
    js.push_back(to);
    std::size_t top = 1;
    double topStress = -INFINITY;
    for (std::size_t k = 1; k + 1 < js.size(); ++k)
      if (const double sk = stressAt(js[k], false); sk > topStress) topStress = sk, top = k;
    if (!(topStress > std::max(first, last))) return std::nullopt;
    const double peak = goldenMaximum([&](double j) { return stressAt(j, false); }, js[top - 1], js[top + 1], 1e-12 * (to - j0));
    if (!(stressAt(peak, true) > std::max(first, last))) return std::nullopt;
    return best;
  }

  // A maximum of the loading branch: above every stress of the run so far. Past the peak a
  // softening band's stress only falls; a "maximum" there is round-off (docs/model.md).
  bool onLoadingBranch(const Voigt& stress) const { return principalStresses(stress).first > highest_; }

  // A stress maximum inside a converged increment of a loading band (the nu > 0 band's traction
  // rises after onset before it softens) gets a row of its own: the increment's path is stable,
  // so opening control from its start traces it. The rest of the increment is then taken from
  // the maximum. Returns false (nothing recorded) if there is none, or if it is not a maximum of
  // the loading branch.
  bool peakInside(int k, const MixedTarget& t, const MaterialPoint& start, const StepOutcome& out) {
    if (!material_.enriched() || !start.band || !point_.band || !(point_.band->integrity < start.band->integrity))
      return false;
    // Opening control traces one band; and a failed band's stress maxima are round-off.
    if (start.secondBand || point_.secondBand || material_.enriched()->bandHasFailed(*start.band)) return false;
    OpeningTarget o;
    o.control = t.control;
    o.stress = t.stress;
    for (int c = 0; c < 3; ++c) o.direction[c] = t.control[c] == Control::Strain ? t.strainIncrement[c] : 0.0;
    const std::optional<BranchState> peak = stressMaximum(o, start, principalStresses(stress_).first, point_.band->normalJump(),
                                                          principalStresses(out.result.stress).first, 1.0);
    if (!peak || !onLoadingBranch(peak->out.step.result.stress)) return false;
    // The rest of the increment from the maximum; the original end stands if it fails.
    MixedTarget rest = t;
    for (int c = 0; c < 3; ++c)
      if (t.control[c] == Control::Strain) rest.strainIncrement[c] = start.strain[c] + t.strainIncrement[c] - peak->point.strain[c];
    MaterialPoint end = peak->point;
    const StepOutcome restOut = mixedControlStep(material_, end, peak->out.step.result.stress, rest, size_, settings_, SnapBackPolicy::Stop);
    if (!restOut.converged()) return false;
    point_ = peak->point;
    record(k, increment_ + 1, peak->out.step, false, false, true, kPeakRow);
    point_ = end;
    record(k, ++increment_, restOut, false, false);
    return true;
  }

  // An intact point whose increment crosses the onset of cracking first steps exactly to the
  // onset, which gets a row of its own (the peak of a brittle point lies there).
  bool stepToOnsetInside(int k, const MixedTarget& t) {
    const BandDamageLaw* law = material_.enriched() ? &material_.enriched()->bandLaw()
                               : material_.smeared() ? &material_.smeared()->law() : nullptr;
    if (!law || point_.band || point_.integrity < 1.0) return true;
    const Voigt d = elasticMixedIncrement(material_.stiffness(), stress_, t);  // the intact point's path
    const std::optional<double> alpha = law->onsetFraction(point_.strain, d);
    if (!alpha || *alpha >= 1.0 || *alpha <= 0.0) return true;
    StepOutcome out;
    out.strainIncrement = *alpha * d * (1.0 + 1e-13);  // just past the root: the onset is met
    out.result = material_.update(point_, out.strainIncrement, size_, SnapBackPolicy::Stop);
    out.dissipation = out.result.dissipation;
    if (!out.converged()) return fail(out, k, 0);
    record(k, increment_ + 1, out, false, false, true, kOnsetRow);
    return true;
  }

  // A state of a trace, to step back to.
  struct Saved {
    MaterialPoint point;
    Voigt stress;
    double work, dissipation, lambda;
  };
  Saved save(double lambda) const { return {point_, stress_, work_, dissipation_, lambda}; }
  void restore(const Saved& s) { point_ = s.point, stress_ = s.stress, work_ = s.work, dissipation_ = s.dissipation; }

  // The increment found no stable equilibrium under strain control (the material's path test,
  // docs/model.md). Trace the branch from the current state under opening control. If the
  // controlled strain reaches the increment's target without turning back, there was no
  // snap-back: the increment is recorded as a normal one. Otherwise the state where it turns
  // back (the limit point) is the last stable state and gets a row; the run then stops, or
  // (jump) follows the branch until the controlled strain reaches the target again and lands.
  bool snapBack(int k, const MixedTarget& t) {
    SnapBackReport& r = run_.snapBack;
    const TwoPhasePoint* model = material_.enriched();
    if (!model) {
      run_.failure = "snap-back reported by a model without a band to trace it";
      return false;
    }
    if (point_.secondBand) return releaseRest(k, t);
    OpeningTarget o;
    o.control = t.control;
    o.direction = t.strainIncrement;
    o.stress = t.stress;
    if (!point_.band) {  // onset inside the failing increment: stop exactly at onset first
      const Voigt target = point_.strain + t.strainIncrement;
      if (!stepToOnset(k, o)) return false;
      o.direction = target - point_.strain;
      for (int c = 0; c < 3; ++c)
        if (t.control[c] == Control::Stress) o.direction[c] = 0.0;
    }
    const double h = model->bandWidth();
    unsigned mask = 0;
    for (int c = 0; c < 3; ++c)
      if (t.control[c] == Control::Stress) mask |= 1u << c;
    double lambda = 0.0, dJump = 1e-4 * h;
    bool turned = false, peaked = false;
    Saved before = save(lambda);
    int stalled = 0;  // consecutive tries whose jump step is at round-off (docs/model.md, "Snap-back on the path")
    for (int guard = 0; guard < 100000; ++guard) {
      stalled = dJump < kStalledJump * h ? stalled + 1 : 0;
      if (stalled > kStalledTries) return traceStalled(lambda);
      MaterialPoint trial = point_;
      o.normalJump = point_.band->normalJump() + dJump;
      const OpeningOutcome out = openingControlStep(*model, trial, o, settings_.tolerance);
      if (!out.step.converged()) {
        dJump *= 0.5;
        if (dJump < 1e-14 * h) return fail(out.step, k, -1);
        continue;
      }
      if (model->opensSecondBand() &&
          model->tangentialStress(*trial.band, out.step.result.stress) >= model->secondBandOnsetStress()) {
        // The traced branch reaches the second band's trigger: the one-band trace ends here.
        MixedTarget rest = t;
        for (int c = 0; c < 3; ++c)
          rest.strainIncrement[c] = t.control[c] == Control::Strain ? (1.0 - lambda) * o.direction[c] : 0.0;
        return releaseRest(k, rest);
      }
      if (!turned) {
        // The limit point lies in this step if the path to the trial state stops being stable
        // (its first unstable state), or, failing that test, if the load factor turned back.
        const std::optional<double> t = model->firstUnstableOnPath(
            *point_.band, model->bandLaw().loadingSurface(point_.band->integrity), trial.band->jump, mask);
        if (t || out.loadFactor < 0.0) {
          turned = true;
          const double start = point_.band->normalJump();
          const bool ok = t ? stepToLimit(k, o, before, start + *t * (o.normalJump - start), lambda, peaked)
                            : limitPoint(k, o, before, o.normalJump, lambda);
          if (!ok) return false;
          if (!r.detected) {
            r.detected = true;
            r.increment = increment_ + 1;
            r.strain = point_.strain;
            r.stressBefore = principalStresses(stress_).first;
          }
          if (scene_.snapBack == SnapBackPolicy::Stop) {
            std::ostringstream msg;
            msg << "snap-back at increment " << increment_ + 1 << " (first principal stress "
                << principalStresses(stress_).first
                << " MPa at the last stable state): no stable branch continues under strain control; use opening control to trace it";
            run_.failure = msg.str();
            return false;
          }
          before = save(lambda);
          dJump = 1e-4 * h;
          continue;
        }
      }
      // Before the limit point, a stress maximum of the traced branch gets a row.
      if (!turned && !peaked && principalStresses(out.step.result.stress).first < principalStresses(stress_).first &&
          principalStresses(stress_).first > principalStresses(before.stress).first) {
        peaked = true;
        const std::optional<BranchState> peak =
            stressMaximum(o, before.point, principalStresses(before.stress).first, o.normalJump,
                          principalStresses(out.step.result.stress).first, INFINITY);
        if (peak) {  // step back and on to the maximum, and trace on from there
          restore(before);
          point_ = peak->point;
          lambda = before.lambda + peak->out.loadFactor;
          accumulate(peak->out.step);
          record(k, increment_ + 1, peak->out.step, true, false, false, kPeakRow);
          continue;
        }
        record(k, increment_ + 1, out.step, true, false, false, kPeakRow);
      }
      if (lambda + out.loadFactor < 1.0) {
        before = save(lambda);
        lambda += out.loadFactor;
        point_ = trial;
        accumulate(out.step);
        dJump = std::min(dJump * 1.5, 1e-2 * h + dJump);
        continue;
      }
      // Land on lambda = 1 within this step: secant on the jump increment.
      double lo = 0.0, hi = dJump, flo = lambda - 1.0, fhi = lambda + out.loadFactor - 1.0;
      OpeningOutcome best = out;
      MaterialPoint landed = trial;
      for (int it = 0; it < 100 && std::abs(flo - fhi) > 0.0; ++it) {
        const double mid = std::clamp(hi - fhi * (hi - lo) / (fhi - flo), lo + 1e-3 * (hi - lo), hi - 1e-3 * (hi - lo));
        MaterialPoint m = point_;
        o.normalJump = point_.band->normalJump() + mid;
        const OpeningOutcome mo = openingControlStep(*model, m, o, settings_.tolerance);
        if (!mo.step.converged()) break;
        const double fm = lambda + mo.loadFactor - 1.0;
        best = mo, landed = m;
        if (std::abs(fm) < 1e-12) break;
        (fm < 0.0 ? (lo = mid, flo = fm) : (hi = mid, fhi = fm));
      }
      point_ = landed;
      accumulate(best.step);
      if (turned && r.increment == increment_ + 1) {
        r.stressAfter = principalStresses(stress_).first;
        r.jumped = true;
      }
      record(k, ++increment_, best.step, true, turned, false);
      return true;
    }
    run_.failure = "snap-back: the stable branch was not reached";
    return false;
  }

  // The trace of a snap-back stalls where the band's opening can no longer grow by more than
  // round-off (kStalledJump of h) over kStalledTries tries in a row: a band fully open (D = 1)
  // under a stress target it cannot carry, which no further step reaches.
  static constexpr double kStalledJump = 1e-9;
  static constexpr int kStalledTries = 200;
  bool traceStalled(double lambda) {
    std::ostringstream msg;
    msg << "snap-back: the trace of the stable branch stalled at increment " << increment_ + 1 << " (normal jump "
        << point_.band->normalJump() << " mm, damage " << point_.band->damage() << ", " << lambda
        << " of the increment done): the band's opening no longer changes the state, and the increment's target is not reached";
    run_.failure = msg.str();
    run_.snapBack.stalled = true;
    return false;
  }

  // A snap-back of a point with two bands (or whose one-band trace meets the second band's
  // trigger) is not traced: the rest of the increment is taken with the release of the explicit
  // MPM, which lands on a stable state at the increment's strain (docs/model.md, "A second band").
  bool releaseRest(int k, const MixedTarget& t) {
    SnapBackReport& r = run_.snapBack;
    const double before = principalStresses(stress_).first;
    if (!r.detected) {
      r.detected = true;
      r.increment = increment_ + 1;
      r.strain = point_.strain;
      r.stressBefore = before;
    }
    if (scene_.snapBack == SnapBackPolicy::Stop) {
      if (!run_.history.empty()) run_.history.back().event |= kLastStableRow;
      std::ostringstream msg;
      msg << "snap-back at increment " << increment_ + 1 << " of a point with two bands (first principal stress "
          << before << " MPa at the last converged state): no stable branch continues under strain control";
      run_.failure = msg.str();
      return false;
    }
    MaterialPoint p = point_;
    const StepOutcome out = mixedControlStep(material_, p, stress_, t, size_, settings_, SnapBackPolicy::Release);
    if (!out.converged()) return fail(out, k, -1);
    point_ = p;
    if (!run_.history.empty()) run_.history.back().event |= kLastStableRow;
    record(k, ++increment_, out, false, true);
    if (r.increment == increment_) {
      r.stressAfter = principalStresses(stress_).first;
      r.jumped = true;
    }
    return true;
  }

  // Step from the current state to the limit point at normal jump `limit` and give it a row
  // (a limit point at the current state marks the row already written there).
  bool stepToLimit(int k, OpeningTarget o, const Saved& before, double limit, double& lambda, bool& peaked) {
    if (limit - point_.band->normalJump() < 1e-9 * material_.enriched()->bandWidth()) {
      if (!run_.history.empty()) run_.history.back().event |= kLastStableRow;
      return true;
    }
    if (!peaked) {
      // A stress maximum between the previous trace state and the limit point (the trace's
      // last step may have landed next to it) gets its row first.
      MaterialPoint probe = before.point;
      o.normalJump = limit;
      const OpeningOutcome atLimit = openingControlStep(*material_.enriched(), probe, o, settings_.tolerance);
      const std::optional<BranchState> peak =
          atLimit.step.converged() ? stressMaximum(o, before.point, principalStresses(before.stress).first, limit,
                                                   principalStresses(atLimit.step.result.stress).first, INFINITY)
                                   : std::nullopt;
      if (peak) {
        peaked = true;
        restore(before);
        point_ = peak->point;
        lambda = before.lambda + peak->out.loadFactor;
        accumulate(peak->out.step);
        record(k, increment_ + 1, peak->out.step, true, false, false, kPeakRow);
      }
    }
    MaterialPoint end = point_;
    o.normalJump = limit;
    const OpeningOutcome out = openingControlStep(*material_.enriched(), end, o, settings_.tolerance);
    if (!out.step.converged()) return fail(out.step, k, -1);
    point_ = end;
    lambda += out.loadFactor;
    accumulate(out.step);
    record(k, increment_ + 1, out.step, true, false, false, kLastStableRow);
    return true;
  }

  // The traced load factor turned back between the state `from` and the normal jump `past`:
  // find its maximum (golden section on the normal jump), the limit point, and step there. A
  // limit point at `from` itself marks the row already written there.
  bool limitPoint(int k, OpeningTarget o, const Saved& from, double past, double& lambda) {
    const TwoPhasePoint* model = material_.enriched();
    const double start = from.point.band->normalJump();
    const auto loadFactor = [&](double jump, OpeningOutcome* outcome, MaterialPoint* end) {
      MaterialPoint m = from.point;
      o.normalJump = jump;
      const OpeningOutcome out = openingControlStep(*model, m, o, settings_.tolerance);
      if (outcome) *outcome = out, *end = m;
      return out.step.converged() ? from.lambda + out.loadFactor : -INFINITY;
    };
    const double best =
        goldenMaximum([&](double j) { return loadFactor(j, nullptr, nullptr); }, start, past, 1e-12 * model->bandWidth());
    restore(from);
    OpeningOutcome out;
    MaterialPoint end;
    if (best - start < 1e-9 * model->bandWidth() || !(loadFactor(best, &out, &end) > from.lambda)) {
      lambda = from.lambda;
      if (!run_.history.empty()) run_.history.back().event |= kLastStableRow;
      return true;
    }
    point_ = end;
    lambda = from.lambda + out.loadFactor;
    accumulate(out.step);
    record(k, increment_ + 1, out.step, true, false, false, kLastStableRow);
    return true;
  }

  bool openingSegment(int k, const Segment& seg) {
    const TwoPhasePoint* model = material_.enriched();
    OpeningTarget o;
    o.control = seg.control;
    o.stress = seg.target;
    for (int c = 0; c < 3; ++c) o.direction[c] = seg.control[c] == Control::Strain ? seg.target[c] : 0.0;
    if (!point_.band && !stepToOnset(k, o)) return false;
    const double jump0 = point_.band->normalJump();
    for (int i = 1; i <= seg.increments; ++i) {
      o.normalJump = openingAt(seg, jump0, i);
      MaterialPoint trial = point_;
      const OpeningOutcome out = openingControlStep(*model, trial, o, settings_.tolerance);
      if (!out.step.converged()) return fail(out.step, k, i);
      point_ = trial;
      record(k, ++increment_, out.step, true, false);
    }
    return true;
  }

  // Elastic, so linear: find the exact onset along the segment's direction and stop there.
  bool stepToOnset(int k, const OpeningTarget& o) {
    const TwoPhasePoint* model = material_.enriched();
    MixedTarget t;
    t.control = o.control;
    t.strainIncrement = o.direction;
    t.stress = o.stress;
    // Full strain increment of the elastic mixed-control step along the direction.
    Voigt d = o.direction;
    std::vector<int> free;
    for (int c = 0; c < 3; ++c)
      if (o.control[c] == Control::Stress) free.push_back(c), d[c] = 0.0;
    const Tangent& a = material_.stiffness();
    for (int pass = 0; pass < 2 && !free.empty(); ++pass)  // exact for up to 3 free components
      for (int c : free) d[c] += (o.stress[c] - stress_[c] - (a * d)[c]) / a(c, c);
    Voigt unit = d;
    for (int it = 0; it < 50 && !free.empty(); ++it) {  // Gauss-Seidel on the free block
      for (int c : free) unit[c] += (o.stress[c] - stress_[c] - (a * unit)[c]) / a(c, c);
    }
    double scale = 1.0;
    std::optional<double> alpha;
    for (int it = 0; it < 200 && !(alpha = model->onsetFraction(point_.strain, scale * unit)); ++it) scale *= 2.0;
    if (!alpha) {
      run_.failure = "opening control: the path never reaches the onset of cracking (compression?)";
      return false;
    }
    StepOutcome out;
    const Voigt step = *alpha * scale * unit * (1.0 + 1e-13);
    out.result = material_.update(point_, step, size_, SnapBackPolicy::Stop);
    out.strainIncrement = step;
    out.dissipation = out.result.dissipation;
    if (!out.converged() || !point_.band) return fail(out, k, 0);
    record(k, ++increment_, out, false, false, true, kOnsetRow);
    return true;
  }

  bool fail(const StepOutcome& out, int k, int i) {
    std::ostringstream msg;
    msg << "increment " << increment_ + 1 << " (segment " << k + 1 << ", step " << i << "): material update "
        << toString(out.result.status) << ", traction residual " << out.result.residual << " MPa after "
        << out.result.iterations << " iterations, stress-control residual " << out.controlResidual << " MPa";
    run_.failure = msg.str();
    return false;
  }

  // Work (trapezoid in the increment) and dissipation of a committed step; then its stress.
  void accumulate(const StepOutcome& out) {
    work_ += 0.5 * (stress_ + out.result.stress).dot(out.strainIncrement);
    dissipation_ += out.dissipation;
    stress_ = out.result.stress;
  }

  // Thrown by record for a row that is not all numbers; run() ends there (the rows before it stay).
  struct NonFiniteRow {
    std::string what;
  };

  void record(int k, int inc, const StepOutcome& out, bool opening, bool jump, bool accumulateStep = true,
              unsigned event = 0) {
    if (accumulateStep && inc > 0) accumulate(out);
    HistoryRow r;
    r.increment = inc;
    r.segment = k + 1;
    r.strain = point_.strain;
    r.stress = stress_;
    r.damage = point_.damage();
    r.integrity = point_.band ? point_.band->integrity : point_.integrity;
    r.work = work_;
    r.dissipation = dissipation_;
    r.iterations = out.iterations;
    r.substeps = out.substeps;
    r.openingControl = opening;
    r.snapBackRelease = jump;
    r.event = event;
    const Tangent& c = compliance_;
    if (point_.band) {
      const BandState& b = *point_.band;
      r.crackNormal = b.crackNormal;
      r.normalJump = b.normalJump();
      r.slidingJump = b.slidingDirection().dot(b.jump);
      r.volumeFraction = b.volumeFraction;
      const Voigt bandStrain = b.onsetStrain + jumpToStrain(b.crackNormal) * b.jump / material_.enriched()->bandWidth();
      r.opening = material_.enriched()->bandWidth() * normalComponent(bandStrain - c * stress_, b.crackNormal);
      if (point_.secondBand) {
        const BandState& s = *point_.secondBand;
        r.secondBand = true;
        r.secondNormal = s.crackNormal;
        r.secondDamage = s.damage();
        r.secondNormalJump = s.normalJump();
        r.secondSlidingJump = s.slidingDirection().dot(s.jump);
      }
    } else if (material_.smeared() && point_.integrity < 1.0) {
      const Vec2 n = principalStresses(stress_).firstDirection;
      r.crackNormal = n;
      r.opening = scene_.effectiveSize * normalComponent(point_.strain - c * stress_, n);
    }
    if (!isAllNumbers(r)) throw NonFiniteRow{notANumberFailure(inc, k + 1)};
    run_.history.push_back(r);
    highest_ = std::max(highest_, principalStresses(stress_).first);
    if (observe_) observe_(r, inc, total_);
  }

  const PointScene& scene_;
  const RowObserver& observe_;
  Material material_;
  Tangent compliance_ = elasticCompliance(scene_.material.elastic);
  EffectiveSize size_;
  MixedControlSettings settings_;
  MaterialPoint point_;
  Voigt stress_ = Voigt::Zero();
  double work_ = 0.0, dissipation_ = 0.0;
  double highest_ = -INFINITY;  // the largest first principal stress of the rows so far (MPa)
  int increment_ = 0, total_ = 0;
  PointRun run_;
};

}  // namespace

int totalIncrements(const PointScene& scene) {
  int n = 0;
  for (const Segment& s : scene.path) n += s.increments;
  return n;
}

void PointScene::validate() const {
  try {
    material.validate();
  } catch (const ParameterError& e) {
    throw io::ValueError("material", e.what());
  }
  if (!(effectiveSize > 0.0 && std::isfinite(effectiveSize))) throw io::ValueError("effective_size", "must be > 0 mm");
  if (material.model == ModelKind::Enriched)
    if (const std::string problem =
            effectiveSizeProblem(effectiveSize, material.bandWidth, material.secondBand == SecondBandOption::Off ? 1 : 2);
        !problem.empty())
      throw io::ValueError("effective_size", problem);
  if (!(relativeTolerance > 0.0 && relativeTolerance <= 1e-3)) throw io::ValueError("tolerance", "must be in (0, 1e-3]");
  if (substepLevels < 0 || substepLevels > 20) throw io::ValueError("substep_levels", "must be in [0, 20]");
  if (path.empty()) throw io::ValueError("path", "needs at least one segment");
  for (const Segment& seg : path) {
    if (seg.openingControl && material.model != ModelKind::Enriched)
      throw io::ValueError("path", std::string("opening control needs a band (model: enriched); this material is ") +
                                       toString(material.model));
    if (seg.openingControl && material.secondBand != SecondBandOption::Off)
      throw io::ValueError("path", "opening control drives the opening of one band; with second_band: orthogonal a point "
                                   "may have two (docs/model.md)");
  }
}

PointRun runPoint(const PointScene& scene, const RowObserver& observe) {
  scene.validate();
  return Runner(scene, observe).run();
}

PointSummary summarise(const PointScene& scene, const PointRun& run) {
  PointSummary s;
  s.effectiveSize = scene.effectiveSize;
  for (const HistoryRow& r : run.history) {
    const double p = principalStresses(r.stress).first;
    if ((r.event & kOnsetRow) && s.onsetStress == 0.0) s.onsetStress = p;
    if (p > s.peakStress) {
      s.peakStress = p;
      s.strainAtPeak = firstPrincipalStrain(r.strain);
    }
  }
  if (!run.history.empty()) {
    s.dissipation = run.history.back().dissipation;
    s.finalWork = run.history.back().work;
  }
  s.energyPerArea = s.effectiveSize * s.dissipation;
  return s;
}

}  // namespace ecm::driver
