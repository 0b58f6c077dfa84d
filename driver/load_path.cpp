#include "driver/load_path.hpp"

#include <cmath>
#include <stdexcept>

namespace ecm::driver {

const std::vector<std::string>& presetNames() {
  static const std::vector<std::string> names = {"uniaxial_tension", "uniaxial_strain", "biaxial",
                                                 "pure_shear", "tension_then_shear", "rotating_principal_axes",
                                                 "cyclic", "compression"};
  return names;
}

namespace {

constexpr auto S = Control::Strain;
constexpr auto T = Control::Stress;

Segment uniaxialStress(double exx, int n) { return {{S, T, T}, Voigt(exx, 0.0, 0.0), n}; }

}  // namespace

std::vector<Segment> presetSegments(const PresetPath& p, double nu) {
  const double e = p.strain;
  const int n = p.increments;
  std::vector<Segment> path;
  if (p.name == "uniaxial_tension") {
    path.push_back(uniaxialStress(e, n));
  } else if (p.name == "compression") {
    path.push_back(uniaxialStress(-std::abs(e), n));
  } else if (p.name == "uniaxial_strain") {
    path.push_back({{S, S, S}, Voigt(e, 0.0, 0.0), n});
  } else if (p.name == "biaxial") {
    path.push_back({{S, S, S}, Voigt(e, p.ratio * e, 0.0), n});
  } else if (p.name == "pure_shear") {
    path.push_back({{S, S, S}, Voigt(0.0, 0.0, e), n});
  } else if (p.name == "tension_then_shear") {
    path.push_back(uniaxialStress(e, n));
    path.push_back({{S, T, S}, Voigt(e, 0.0, p.shear), n});  // mixed mode: hold eps_xx, shear
  } else if (p.name == "rotating_principal_axes") {
    // eps(theta) = e R(theta) diag(1, -nu) R(theta)^T, theta from 0 to `angle`, n segments.
    for (int k = 1; k <= n; ++k) {
      const double theta = p.angle * k / n;
      path.push_back({{S, S, S}, rotateStrain(Voigt(e, -nu * e, 0.0), theta), 1});
    }
    path.insert(path.begin(), Segment{{S, S, S}, Voigt(e, -nu * e, 0.0), n});
  } else if (p.name == "cyclic") {
    for (double peak : p.cycleStrains) {
      path.push_back(uniaxialStress(peak, n));
      path.push_back(uniaxialStress(0.0, n));  // unload to zero strain: secant to the origin
    }
  } else {
    throw std::invalid_argument("unknown preset path '" + p.name + "'");
  }
  if (p.opening > 0.0) {
    Segment open = path.front();
    open.openingControl = true;
    open.openingTarget = p.opening;
    open.firstOpeningIncrement = p.firstOpeningIncrement;
    path.push_back(open);
  }
  return path;
}

double openingAt(const Segment& s, double start, int k) {
  const double total = s.openingTarget - start;
  const int n = s.increments;
  const double first = s.firstOpeningIncrement;
  if (!(first > 0.0) || first * n >= total) return start + total * k / n;
  // ratio q > 1 with first (q^n - 1)/(q - 1) = total, by bisection on log q
  double lo = 0.0, hi = 50.0 / n;
  const auto sum = [&](double logq) { return first * std::expm1(n * logq) / std::expm1(logq); };
  for (int it = 0; it < 200; ++it) {
    const double mid = 0.5 * (lo + hi);
    (sum(mid) < total ? lo : hi) = mid;
  }
  const double logq = 0.5 * (lo + hi);
  return k == n ? s.openingTarget : start + first * std::expm1(k * logq) / std::expm1(logq);
}

}  // namespace ecm::driver
