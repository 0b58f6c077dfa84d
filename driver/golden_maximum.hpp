#pragma once
// The argument of the maximum of a unimodal function on an interval (golden section), for the
// drivers' stress-maximum rows (docs/inputs.md: a stress maximum gets a row of its own).
#include <cmath>

namespace ecm::driver {

// The argument of the maximum of a unimodal f on [lo, hi], to `tolerance`.
template <class F>
double goldenMaximum(const F& f, double lo, double hi, double tolerance) {
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  double a = hi - g * (hi - lo), b = lo + g * (hi - lo), fa = f(a), fb = f(b);
  for (int it = 0; it < 80 && hi - lo > tolerance; ++it) {
    if (fa > fb) hi = b, b = a, fb = fa, a = hi - g * (hi - lo), fa = f(a);
    else lo = a, a = b, fa = fb, b = lo + g * (hi - lo), fb = f(b);
  }
  return 0.5 * (lo + hi);
}

}  // namespace ecm::driver
