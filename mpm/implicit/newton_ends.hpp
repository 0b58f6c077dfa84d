#pragma once
// When an attempt's Newton gives up before max_iterations, from its iterates' relative residuals
// (docs/implicit.md, "Load steps"). Pure functions of the residuals so far, the last one last.
#include <algorithm>
#include <cstddef>
#include <vector>

namespace ecm::mpm {

// Newton proper (a factorisation at every iteration) has stalled when its relative residual did
// not halve over the last kStallWindow iterations: converging, it halves it at every iteration
// or two. (With a kept factorisation the test cost more halvings than it saved: left to
// max_iterations there, as is the last halving's try.)
inline constexpr int kStallWindow = 6;
inline bool stalled(const std::vector<double>& residuals) {
  const std::size_t n = residuals.size();
  return n > kStallWindow && residuals[n - 1] > 0.5 * residuals[n - 1 - kStallWindow];
}

// Newton has left the step's basin when an iterate's relative residual is at least
// kDivergedResidual and kDivergedFactor times the lowest of the attempt's earlier iterates
// ("Newton that leaves its basin"): such an iterate carries points far past their state, its
// trial releases them by the hundred, and each further iteration costs more than the attempt is
// worth. Every try tests it, the last halving's too.
inline constexpr double kDivergedResidual = 0.5;
inline constexpr double kDivergedFactor = 100.0;
inline bool diverged(const std::vector<double>& residuals) {
  if (residuals.size() < 2) return false;
  const double last = residuals.back();
  const double lowest = *std::min_element(residuals.begin(), residuals.end() - 1);
  return last >= kDivergedResidual && last >= kDivergedFactor * lowest;
}

}  // namespace ecm::mpm
