#pragma once
// Where in an increment a band opens (docs/model.md pitfall 1), the same in 2D and 3D: the
// fraction alpha of the increment at which the intact driving force Y(a : (eps + alpha d eps))
// reaches its onset value. Y is piecewise quadratic in alpha (its positive parts switch), so the
// root is bracketed and found by Illinois regula falsi, not by Newton.
#include <cmath>
#include <optional>

#include "material/illinois.hpp"

namespace ecm {

// excess(alpha) = Y(alpha) - yOnset. nullopt when Y stays below the onset over the increment; 0
// when it is there at the start; otherwise the fraction where |excess| <= 1e-15 yOnset, or the
// end of the final bracket at which the criterion is met.
template <class Excess>
std::optional<double> onsetFractionOf(Excess&& excess, double yOnset) {
  const double gb = excess(1.0);
  if (gb < 0.0) return std::nullopt;
  const double ga = excess(0.0);
  if (ga >= 0.0) return 0.0;
  double a = 0.0, b = 1.0, last = 1.0;
  const bool found = illinois([&](double c) { return excess(last = c); }, a, b, ga, gb, 200,
                              [](double lo, double hi) { return hi - lo > 1e-15; },
                              [&](double g) { return std::abs(g) <= 1e-15 * yOnset; });
  return found ? last : b;
}

}  // namespace ecm
