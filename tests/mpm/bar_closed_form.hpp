#pragma once
// The closed form of a bar (nu = 0, length L) in uniaxial tension that cracks in one band:
// elastic up to f_t', then the band's branch delta = sigma L / E + w(sigma), w the band's
// inelastic opening (material/uniaxial_closed_form.hpp), sampled over the integrity
// x = 10^lx, lx from 0 to -8 in steps of `logStep`. Shared by the explicit cracked block and the
// implicit snap-back bar.
#include <algorithm>
#include <cmath>
#include <vector>

#include "material/uniaxial_closed_form.hpp"
#include "material/voigt.hpp"

namespace ecm::mpm::test {

struct BarClosedForm {
  std::vector<double> delta, sigma;  // mm, MPa
  double d0 = 1.0, s0 = 1.0;         // f_t' L / E and f_t': the units of distance()

  BarClosedForm(const DamageLawParams& law, double length, double bandWidth, double logStep) {
    d0 = law.tensileStrength * length / law.youngsModulus;
    s0 = law.tensileStrength;
    delta.push_back(0.0), sigma.push_back(0.0);
    for (double lx = 0.0; lx > -8.0; lx -= logStep) {
      const UniaxialBandPoint p = uniaxialBandResponse(law, 0.0, bandWidth, std::pow(10.0, lx));
      delta.push_back(p.stress * length / law.youngsModulus + p.opening);
      sigma.push_back(p.stress);
    }
  }
  // Distance of (d, s) to the curve, with delta in units of f_t' L / E and sigma in units of
  // f_t': on a steep (or snapping-back) branch a stress difference at equal delta would mostly
  // measure a tiny lag in delta, or not be defined.
  double distance(double d, double s) const {
    double best = INFINITY;
    const Vec2 q(d / d0, s / s0);
    for (std::size_t k = 1; k < delta.size(); ++k) {
      const Vec2 a(delta[k - 1] / d0, sigma[k - 1] / s0), b(delta[k] / d0, sigma[k] / s0);
      const double t = std::clamp((q - a).dot(b - a) / std::max((b - a).squaredNorm(), 1e-300), 0.0, 1.0);
      best = std::min(best, (a + t * (b - a) - q).norm());
    }
    return best;
  }
  // sigma at delta on a curve that does not snap back.
  double operator()(double d) const {
    const auto it = std::upper_bound(delta.begin(), delta.end(), d);
    if (it == delta.end()) return sigma.back();
    const std::size_t k = static_cast<std::size_t>(it - delta.begin());
    const double t = (d - delta[k - 1]) / (delta[k] - delta[k - 1]);
    return sigma[k - 1] + t * (sigma[k] - sigma[k - 1]);
  }
};

}  // namespace ecm::mpm::test
