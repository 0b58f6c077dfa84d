#pragma once
// Newton on a piecewise smooth residual (docs/implicit.md, "Cycling Newton"). A point's stress
// has a kink where it switches between loading and unloading its band; with a few points at
// their kinks, Newton with the consistent tangent can cycle between two iterates, one on each
// side, at any step size. The guard flags the points that switch while the residual grows after
// a step solved with a fresh tangent: they take their secant tangent (the damage frozen, stiffer
// than the softening one), so that the iterates approach their kinks from one side. Once the
// residual has fallen over kSettled iterations in a row, the flags are dropped and Newton goes
// on with the consistent tangent (quadratic again, if the set of loading points has settled).
#include <cmath>
#include <cstdint>
#include <vector>

namespace ecm::mpm {

class CycleGuard {
 public:
  static constexpr int kSettled = 3;

  // Per particle: 1 where the next trial should use the secant tangent; nullptr while none.
  const std::vector<std::uint8_t>* secantFlags() const { return secant_.empty() ? nullptr : &secant_; }
  // Whether the step about to be solved uses a tangent factorised at the current iterate.
  void solvedWithFreshTangent(bool fresh) { fresh_ = fresh; }
  // A new iterate: its points' dissipation in the trial (> 0: loading) and its relative residual.
  void observe(const std::vector<double>& dissipation, double relative) {
    std::vector<std::uint8_t> loading(dissipation.size());
    for (std::size_t i = 0; i < loading.size(); ++i) loading[i] = dissipation[i] > 0.0 ? 1 : 0;
    const bool comparable = wasLoading_.size() == loading.size();
    if (fresh_ && comparable && relative > previous_) {
      for (std::size_t i = 0; i < loading.size(); ++i) {
        if (loading[i] == wasLoading_[i]) continue;
        if (secant_.empty()) secant_.assign(loading.size(), 0);
        secant_[i] = 1;
      }
    }
    falling_ = relative < previous_ ? falling_ + 1 : 0;
    if (falling_ >= kSettled) secant_.clear();
    wasLoading_ = std::move(loading);
    previous_ = relative;
  }

 private:
  std::vector<std::uint8_t> secant_, wasLoading_;  // per particle
  double previous_ = INFINITY;                     // the last iterate's relative residual
  bool fresh_ = false;
  int falling_ = 0;                                // iterations since the residual last grew
};

}  // namespace ecm::mpm
