#pragma once
// Test helper: drive a constitutive update in uniaxial stress (sigma_yy = sigma_xy = 0) with
// eps_xx prescribed. Newton on (eps_yy, gamma_xy) with the returned consistent tangent; where
// the tangent jumps (onset), fall back to the elastic stiffness (a contraction, since the
// material is never stiffer than elastic).
#include <cmath>
#include <functional>
#include <optional>

#include "material/update_result.hpp"

namespace ecm::test {

// update(increment, commit): runs the model from the committed state; commits if `commit`.
using TrialUpdate = std::function<UpdateResult(const Voigt& increment, bool commit)>;

inline std::optional<UpdateResult> uniaxialStressStep(const TrialUpdate& update, double dExx, const Tangent& elastic,
                                                      double tol, Voigt* increment = nullptr) {
  Voigt d(dExx, 0.0, 0.0);
  d[1] = -elastic(1, 0) / elastic(1, 1) * dExx;
  bool elasticFallback = false;
  double previous = INFINITY;
  for (int it = 0; it < 4000; ++it) {
    const UpdateResult r = update(d, false);
    if (!r.converged()) return std::nullopt;
    const Vec2 res(r.stress[1], r.stress[2]);
    if (res.norm() <= tol) {
      update(d, true);
      if (increment) *increment = d;
      return r;
    }
    elasticFallback = elasticFallback || res.norm() > 0.5 * previous;
    previous = res.norm();
    const Mat2 k = elasticFallback ? Mat2(elastic.bottomRightCorner<2, 2>()) : Mat2(r.tangent.bottomRightCorner<2, 2>());
    const Vec2 step = k.partialPivLu().solve(res);
    d[1] -= step[0];
    d[2] -= step[1];
  }
  return std::nullopt;
}

}  // namespace ecm::test
