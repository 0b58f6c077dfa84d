#pragma once
// What the caller of an enriched point's update asks of it besides the increment: the snap-back
// policy, the tangent, mixed control, sub-stepping and a crack normal chosen by the caller.
#include "material/snap_back_policy.hpp"
#include "material/voigt.hpp"

namespace ecm {

// What the caller of an update needs besides the stress and the new state.
struct UpdateOptions {
  SnapBackPolicy snapBack = kDefaultSnapBack;  // material/snap_back_policy.hpp
  bool tangent = true;  // the consistent tangent of Eq. (10); an explicit solver does not use it
  // Bit i set: the caller holds Voigt stress component i fixed (mixed control) and solves for
  // its strain. A state is then stable only if the consistent tangent's block of these
  // components is positive definite as well as K of Eq. (9) (docs/model.md).
  unsigned stressControlled = 0;
  // A NotConverged update is retried in 2, 4, ... 2^substepLevels equal sub-steps (0: never).
  // Only Material::update sub-steps (material/material.hpp); the TwoPhasePoint calls ignore it.
  int substepLevels = 0;
  // The crack normal a band that opens in this update takes (a caller that tracks crack paths:
  // docs/model.md, "Crack paths"); nullptr: the first principal direction of the stress at onset.
  const Vec2* onsetNormal = nullptr;
  UpdateOptions() = default;
  UpdateOptions(SnapBackPolicy policy, bool withTangent = true) : snapBack(policy), tangent(withTangent) {}  // NOLINT: implicit
};

}  // namespace ecm
