#pragma once
// The snap-back release's search (docs/model.md, "Snap-back on the path"), the same in 2D and 3D.
// With the damage frozen at x, traction continuity (Eq. 6) is linear in the jump, and
// g(x) = Y([u](x)) / F(x) - 1 changes sign between the band's integrity x0 (g > 0) and x -> 0
// (F ~ x^-2n, Y bounded). The scan steps x down geometrically; each sign change is solved by
// Illinois regula falsi in log x, and the first root the caller confirms stable is taken.
#include <cmath>

#include "material/illinois.hpp"

namespace ecm {

inline constexpr int kMaxReleaseSteps = 2000;     // scan steps of the release, x0 * ratio^k
inline constexpr double kReleaseScanRatio = 0.9;  // (0.9^2000 ~ 1e-92: down to a failed band)

// probe(x) returns a probe with .g (g at x) and .band.integrity (x); confirm(root probe) is true
// where it takes the root (the caller keeps its result). `probes` counts the probes after the
// first. True when a root was taken.
template <class Probe, class Confirm>
bool releaseScan(Probe&& probe, double x0, int& probes, Confirm&& confirm) {
  auto hi = probe(x0);
  for (int k = 0; k < kMaxReleaseSteps && hi.band.integrity > 1e-300; ++k) {
    auto lo = probe(hi.band.integrity * kReleaseScanRatio);
    ++probes;
    if (!(lo.g <= 0.0) || !(hi.g > 0.0)) {
      hi = lo;
      continue;
    }
    double la = std::log(lo.band.integrity), lb = std::log(hi.band.integrity);
    auto root = lo;
    illinois(
        [&](double lc) {
          root = probe(std::exp(lc));
          ++probes;
          return root.g;
        },
        la, lb, lo.g, hi.g, 100, [](double a, double b) { return b - a > 1e-15 * std::abs(b) + 1e-300; },
        [](double g) { return std::abs(g) <= 1e-14; });
    if (confirm(root)) return true;
    hi = lo;  // unstable root: look further down
  }
  return false;
}

}  // namespace ecm
