#include "driver/mixed_control.hpp"

#include <cmath>
#include <vector>

namespace ecm::driver {

namespace {

using FreeVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 3, 1>;

// The stress-controlled components' block of k solved against rhs: k_ss x = rhs_s.
FreeVector solveFree(const Tangent& k, const Voigt& rhs, const std::vector<int>& free) {
  const int m = static_cast<int>(free.size());
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 3, 3> kk(m, m);
  FreeVector r(m);
  for (int i = 0; i < m; ++i) {
    r[i] = rhs[free[i]];
    for (int j = 0; j < m; ++j) kk(i, j) = k(free[i], free[j]);
  }
  return kk.partialPivLu().solve(r);
}

std::vector<int> stressControlled(const MixedTarget& t) {
  std::vector<int> free;
  for (int i = 0; i < 3; ++i)
    if (t.control[i] == Control::Stress) free.push_back(i);
  return free;
}

// One attempt without sub-stepping.
StepOutcome solveIncrement(const PointUpdate& update, const Tangent& a, const MaterialPoint& start, MaterialPoint& end,
                           const Voigt& currentStress, const MixedTarget& t, const MixedControlSettings& s) {
  const std::vector<int> free = stressControlled(t);
  const int m = static_cast<int>(free.size());
  StepOutcome out;
  Voigt d = elasticMixedIncrement(a, currentStress, t);
  bool elasticFallback = false;
  double previous = INFINITY;
  for (int it = 0; it <= s.maxIterations; ++it) {
    end = start;
    out.result = update(end, d);
    out.strainIncrement = d;
    out.iterations = it;
    if (!out.result.converged()) return out;
    Voigt res = Voigt::Zero();
    for (int i : free) res[i] = out.result.stress[i] - t.stress[i];
    out.controlResidual = res.norm();
    // The stress of the end strain cannot be closer than the round-off of that strain times
    // the stiffness, which a thin bulk makes huge (f near 1, docs/model.md).
    const Voigt endStrain = start.strain + d;
    const double roundOff = TwoPhasePoint::kRoundOff * (out.result.tangent.cwiseAbs() * endStrain.cwiseAbs()).maxCoeff();
    if (out.controlResidual <= s.tolerance + roundOff) {
      out.dissipation = out.result.dissipation;
      return out;
    }
    // Newton with the consistent tangent; the elastic stiffness once it stops contracting.
    elasticFallback = elasticFallback || out.controlResidual > 0.5 * previous;
    previous = out.controlResidual;
    const FreeVector x = solveFree(elasticFallback ? a : out.result.tangent, res, free);
    for (int i = 0; i < m; ++i) d[free[i]] -= x[i];
  }
  out.result.status = UpdateStatus::NotConverged;
  return out;
}

StepOutcome substepped(const PointUpdate& update, const Tangent& a, MaterialPoint& point, const Voigt& currentStress,
                       const MixedTarget& t, const MixedControlSettings& s, int level) {
  MaterialPoint end;
  StepOutcome out = solveIncrement(update, a, point, end, currentStress, t, s);
  if (out.converged()) {
    point = end;
    return out;
  }
  // A snap-back is a property of the path, not of the step size: do not sub-step it.
  if (out.result.status == UpdateStatus::SnapBack || level >= s.maxSubstepLevels) return out;
  MixedTarget half = t;
  half.strainIncrement = 0.5 * t.strainIncrement;
  half.stress = 0.5 * (currentStress + t.stress);
  MaterialPoint trial = point;
  StepOutcome first = substepped(update, a, trial, currentStress, half, s, level + 1);
  if (!first.converged()) return first;
  StepOutcome second =
      substepped(update, a, trial, first.result.stress, {t.control, half.strainIncrement, t.stress}, s, level + 1);
  if (!second.converged()) return second;
  point = trial;
  second.strainIncrement += first.strainIncrement;
  second.dissipation += first.dissipation;
  second.iterations += first.iterations;
  second.substeps = first.substeps + second.substeps;
  return second;
}

}  // namespace

Voigt elasticMixedIncrement(const Tangent& k, const Voigt& currentStress, const MixedTarget& t) {
  const std::vector<int> free = stressControlled(t);
  Voigt d = t.strainIncrement;
  if (free.empty()) return d;
  for (int i : free) d[i] = 0.0;
  const FreeVector x = solveFree(k, t.stress - currentStress - k * d, free);  // k_ss d_s = dsigma_s - k_sk d_k
  for (std::size_t i = 0; i < free.size(); ++i) d[free[i]] = x[static_cast<int>(i)];
  return d;
}

StepOutcome mixedControlStep(const PointUpdate& update, const Tangent& elastic, MaterialPoint& point,
                             const Voigt& currentStress, const MixedTarget& target, const MixedControlSettings& s) {
  return substepped(update, elastic, point, currentStress, target, s, 0);
}

}  // namespace ecm::driver
