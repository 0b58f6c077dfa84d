#include "material/damage_function.hpp"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "material/parameter_check.hpp"

namespace ecm {

void DamageLawParams::validate() const {
  requireInRange("youngs_modulus E (MPa)", youngsModulus, 0.0, 1e300);
  requireInRange("tensile_strength ft (MPa)", tensileStrength, 0.0, 1e300);
  requireInRange("softening_modulus Ep (MPa)", softeningModulus, 0.0, 1e300);
  requireInRange("softening_exponent n", softeningExponent, 0.0, 0.5);
  // The strain at onset, f_t' / E, a number (a denormal E made it infinite and the update crawl
  // through its sub-steps: found by fuzz/fuzz_umat.cpp). Onset strains far above 1 stay allowed:
  // the extremes tests hold the update finite there.
  requireInRange("tensile_strength / youngs_modulus (the strain at onset ft / E)", tensileStrength / youngsModulus, 0.0, 1e300);
}

namespace {
double elasticLimitEnergy(const DamageLawParams& p) {
  return p.tensileStrength * p.tensileStrength / (2.0 * p.youngsModulus);
}
}  // namespace

double damageFunction(const DamageLawParams& p, double x) {
  return damageFunction(p, x, std::pow(x, p.softeningExponent));
}

double damageFunction(const DamageLawParams& p, double x, double s) {
  const double g = (p.youngsModulus + p.softeningModulus * s) / (p.youngsModulus * x + p.softeningModulus * s);
  return elasticLimitEnergy(p) * g * g;  // Eq. (13)
}

double damageFunctionSlope(const DamageLawParams& p, double x) {
  return damageFunctionSlope(p, x, std::pow(x, p.softeningExponent));
}

double damageFunctionSlope(const DamageLawParams& p, double x, double s) {
  const double e = p.youngsModulus, ep = p.softeningModulus, n = p.softeningExponent;
  const double ds = n * s / x;
  const double num = e + ep * s, den = e * x + ep * s;
  const double g = num / den;
  const double dg = (ep * ds * den - num * (e + ep * ds)) / (den * den);
  return 2.0 * elasticLimitEnergy(p) * g * dg;
}

double integrityForDrivingForce(const DamageLawParams& p, double y, double x0) {
  return y > damageFunction(p, x0) ? solveIntegrity(p, y, x0) : x0;
}

double solveIntegrity(const DamageLawParams& p, double y, double x0) {
  return solveIntegrity(p, y, PoweredIntegrity{x0, std::pow(x0, p.softeningExponent)}).x;
}

PoweredIntegrity solveIntegrity(const DamageLawParams& p, double y, const PoweredIntegrity& start) {
  const double e = p.youngsModulus, ep = p.softeningModulus, n = p.softeningExponent;
  const double r = std::sqrt(2.0 * e * y) / p.tensileStrength;  // r >= g(x0) >= 1
  // phi(s) = E - r E s^(1/n) - (r - 1) E_p s, concave and decreasing in s = x^n.
  double s = start.xn, xs = start.x;
  // Each term alone bounds the root from above, s* <= sUpper <= 2 s* (at the root the larger term
  // is at least E/2). From a start far above, the Newton step lands on s* as s - (s - s*), which
  // loses s* to round-off once s* < 1e-16 s (a huge increment at D near 1): start from sUpper.
  const double sUpper = std::min(r > 1.0 ? e / ((r - 1.0) * ep) : 1.0, std::pow(r, -n));
  if (s > 1e3 * sUpper) {
    s = sUpper;
    xs = std::pow(s, 1.0 / n);
  }
  for (int it = 0; it < 200; ++it) {
    const double phi = e - r * e * xs - (r - 1.0) * ep * s;
    const double dphi = -r * e * xs / (n * s) - (r - 1.0) * ep;
    const double next = s - phi / dphi;  // < s while phi < 0
    // Quadratic convergence: the error after a step of relative size d is ~ (1/n - 1)/2 d^2
    // relative (from phi''/phi'), below 1e-17 once d < 1e-9: take that step and stop.
    if (!(next < s) || s - next <= 1e-9 * s) {
      if (next < s) {  // the last step
        s = std::max(next, 0.0);
        xs = std::pow(s, 1.0 / n);
      }
      break;
    }
    s = next;
    xs = std::pow(s, 1.0 / n);
  }
  return {xs, s};
}

namespace {
// F(x) dx/dt for x = t^m, m = 1/(1 - 2n), written without the singular factors:
// F(x) x^(2n) = k (E + E_p x^n)^2 / (E x^(1-n) + E_p)^2 and m t^(m-1) x^(-2n) = m, so the
// integrand is smooth and finite on the whole of [0, 1].
double regularIntegrand(const DamageLawParams& p, double m, double t) {
  const double s = std::pow(t, m * p.softeningExponent);           // x^n
  const double q = std::pow(t, m * (1.0 - p.softeningExponent));   // x^(1-n)
  const double num = p.youngsModulus + p.softeningModulus * s;
  const double den = p.youngsModulus * q + p.softeningModulus;
  return m * elasticLimitEnergy(p) * num * num / (den * den);
}
}  // namespace

double dissipationBetween(const DamageLawParams& p, double xOld, double xNew) {
  if (!(xNew < xOld)) return 0.0;
  if (xNew > 0.95 * xOld) {
    // An ordinary increment (x changes by < 5 %): F is smooth on it, 3-point Gauss-Legendre in x
    // directly (relative error < 1e-12 there; three pow calls instead of eight).
    constexpr double g = 0.7745966692414834, w0 = 8.0 / 9.0, w1 = 5.0 / 9.0;
    const double half = 0.5 * (xOld - xNew), mid = 0.5 * (xOld + xNew);
    return half * (w1 * damageFunction(p, mid - half * g) + w0 * damageFunction(p, mid) + w1 * damageFunction(p, mid + half * g));
  }
  // x = t^m, m = 1/(1 - 2n). The integrand is bounded but steps from m k (E/E_p)^2 near t = 0
  // down to m k near t = 1, so a wide interval is cut into panels of ratio 1.2 in t (4-point
  // Gauss-Legendre each, rel. error ~1e-10); an ordinary increment is a single panel.
  const double m = 1.0 / (1.0 - 2.0 * p.softeningExponent);
  const double ta = std::pow(xNew, 1.0 / m), tb = std::pow(xOld, 1.0 / m);
  static constexpr std::array<double, 4> node = {-0.8611363115940526, -0.3399810435848563,
                                                 0.3399810435848563, 0.8611363115940526};
  static constexpr std::array<double, 4> weight = {0.3478548451374538, 0.6521451548625461,
                                                   0.6521451548625461, 0.3478548451374538};
  const auto panel = [&](double lo, double hi) {
    const double half = 0.5 * (hi - lo), mid = 0.5 * (hi + lo);
    if (hi < 1.05 * lo) {  // a narrow panel (an ordinary increment): 3-point Gauss, rel. ~1e-12
      constexpr double g = 0.7745966692414834, w0 = 8.0 / 9.0, w1 = 5.0 / 9.0;
      return half * (w1 * regularIntegrand(p, m, mid - half * g) + w0 * regularIntegrand(p, m, mid) +
                     w1 * regularIntegrand(p, m, mid + half * g));
    }
    double sum = 0.0;
    for (int i = 0; i < 4; ++i) sum += weight[i] * regularIntegrand(p, m, mid + half * node[i]);
    return sum * half;
  };
  double total = 0.0, hi = tb;
  // Below 1e-12 tb the integrand is flat at its t = 0 value: one last panel covers the rest.
  constexpr double ratio = 1.2;
  // (Among subnormal numbers hi / 1.2 can round back to hi: stop at the smallest normal double.)
  while (hi > ratio * ta && hi > 1e-12 * tb && hi > std::numeric_limits<double>::min()) {
    total += panel(hi / ratio, hi);
    hi /= ratio;
  }
  return total + panel(ta, hi);
}

double dissipationBetween(const DamageLawParams& p, double xOld, double xNew, double fOld, double fNew) {
  if (!(xNew < xOld)) return 0.0;
  if (xNew <= 0.999 * xOld) return dissipationBetween(p, xOld, xNew);
  return (xOld - xNew) / 6.0 * (fOld + 4.0 * damageFunction(p, 0.5 * (xOld + xNew)) + fNew);
}

double dissipationToFailure(const DamageLawParams& p) {
  p.validate();
  struct Ctx {
    const DamageLawParams* p;
    double m;
  } ctx{&p, 1.0 / (1.0 - 2.0 * p.softeningExponent)};
  gsl_function fn;
  fn.function = [](double t, void* c) {
    const auto* k = static_cast<const Ctx*>(c);
    return regularIntegrand(*k->p, k->m, t);
  };
  fn.params = &ctx;
  gsl_integration_workspace* ws = gsl_integration_workspace_alloc(200);
  double result = 0.0, abserr = 0.0;
  gsl_error_handler_t* old = gsl_set_error_handler_off();
  const int status = gsl_integration_qag(&fn, 0.0, 1.0, 0.0, 1e-11, 200, GSL_INTEG_GAUSS31, ws, &result, &abserr);
  gsl_set_error_handler(old);
  gsl_integration_workspace_free(ws);
  if (status != GSL_SUCCESS && abserr > 1e-8 * std::abs(result))
    throw std::runtime_error(std::string("band energy quadrature failed: ") + gsl_strerror(status));
  return result;
}

double uniaxialStress(const DamageLawParams& p, double x) {
  return x * std::sqrt(2.0 * p.youngsModulus * damageFunction(p, x));
}

}  // namespace ecm
