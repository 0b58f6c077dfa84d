#include "calibration/softening_curve.hpp"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_roots.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "calibration/calibration_error.hpp"

namespace ecm::calibration {

namespace {
// Below this log x the integrity is zero for all purposes (x ~ 1e-304).
constexpr double kLogIntegrityFloor = -700.0;
}  // namespace

SofteningCurve::SofteningCurve(const DamageLawParams& law, double width) : law_(law), width_(width) {
  law_.validate();
  if (!(width > 0.0) || !std::isfinite(width)) throw CalibrationError("softening curve: width must be > 0");
}

SofteningPoint SofteningCurve::at(double x) const {
  SofteningPoint p;
  p.stress = uniaxialStress(law_, x);                      // sigma = x sqrt(2 E F(x)), Eqs. (11), (13)
  p.bandStrain = p.stress / (x * law_.youngsModulus);       // eps_L = sigma / ((1 - D) E), Eq. (11)
  p.opening = width_ * (p.bandStrain - p.stress / law_.youngsModulus);  // w = h (eps_L - sigma/E)
  p.damage = 1.0 - x;
  return p;
}

double SofteningCurve::opening(double x) const { return at(x).opening; }

template <class G>
double SofteningCurve::solveLogIntegrity(const G& g, double lo, double hi) const {
  struct Ctx {
    const G* g;
  } ctx{&g};
  gsl_function fn;
  fn.function = [](double lx, void* c) { return (*static_cast<Ctx*>(c)->g)(lx); };
  fn.params = &ctx;
  gsl_root_fsolver* s = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
  gsl_error_handler_t* old = gsl_set_error_handler_off();
  int status = gsl_root_fsolver_set(s, &fn, lo, hi);
  double root = 0.5 * (lo + hi);
  for (int it = 0; it < 200 && status == GSL_SUCCESS; ++it) {
    status = gsl_root_fsolver_iterate(s);
    root = gsl_root_fsolver_root(s);
    if (gsl_root_test_interval(gsl_root_fsolver_x_lower(s), gsl_root_fsolver_x_upper(s), 1e-13, 0.0) == GSL_SUCCESS)
      break;
  }
  gsl_set_error_handler(old);
  gsl_root_fsolver_free(s);
  if (status != GSL_SUCCESS) throw std::runtime_error(std::string("softening curve inversion: ") + gsl_strerror(status));
  return root;
}

namespace {
// For g increasing in log x with g(hi) >= 0: steps down from hi (doubling the step) until
// g(lo) <= 0, moving hi along so that [lo, hi] stays tight. False if g stays positive down to
// x ~ 1e-304 (the target lies beyond any representable integrity: the band is fully damaged).
template <class G>
bool bracketBelow(const G& g, double& lo, double& hi) {
  double step = 1.0;
  lo = std::max(hi - step, kLogIntegrityFloor);
  while (g(lo) > 0.0) {
    if (lo <= kLogIntegrityFloor) return false;
    hi = lo;
    step *= 2.0;
    lo = std::max(hi - step, kLogIntegrityFloor);
  }
  return true;
}
}  // namespace

double SofteningCurve::integrityAtOpening(double w) const {
  if (!(w > 0.0)) return 1.0;
  const auto g = [&](double lx) { return w - opening(std::exp(lx)); };  // increases with x; g(0) = w
  double lo = 0.0, hi = 0.0;
  if (!bracketBelow(g, lo, hi)) return 0.0;
  return std::exp(solveLogIntegrity(g, lo, hi));
}

double SofteningCurve::integrityAtStress(double sigma) const {
  if (!(sigma > 0.0)) return 0.0;
  if (sigma >= law_.tensileStrength) return 1.0;
  const auto g = [&](double lx) { return uniaxialStress(law_, std::exp(lx)) - sigma; };  // increases with x
  double lo = 0.0, hi = 0.0;
  if (!bracketBelow(g, lo, hi)) return 0.0;
  return std::exp(solveLogIntegrity(g, lo, hi));
}

double SofteningCurve::openingAtStressFraction(double fraction) const {
  if (!(fraction > 0.0 && fraction <= 1.0)) throw CalibrationError("stress fraction must be in (0, 1]");
  return opening(integrityAtStress(fraction * law_.tensileStrength));
}

std::vector<double> SofteningCurve::stressesAtOpenings(const std::vector<double>& w) const {
  std::vector<double> out(w.size(), 0.0);
  double hi = 0.0;  // log x at the previous opening: the next root lies at or below it
  for (std::size_t i = 0; i < w.size(); ++i) {
    if (i > 0 && !(w[i] >= w[i - 1])) throw CalibrationError("stressesAtOpenings: openings must not decrease");
    if (!(w[i] > 0.0)) {
      out[i] = uniaxialStress(law_, 1.0);
      continue;
    }
    if (i > 0 && w[i] == w[i - 1]) {
      out[i] = out[i - 1];
      continue;
    }
    const auto g = [&](double lx) { return w[i] - opening(std::exp(lx)); };
    if (!(g(hi) >= 0.0)) hi = 0.0;  // the previous root fell a rounding error beyond this one
    double lo = hi;
    if (!bracketBelow(g, lo, hi)) break;  // this and all later openings: sigma = 0
    hi = solveLogIntegrity(g, lo, hi);
    out[i] = uniaxialStress(law_, std::exp(hi));
  }
  return out;
}

std::vector<SofteningPoint> SofteningCurve::sample(double maxOpening, int count) const {
  std::vector<double> w(static_cast<std::size_t>(std::max(count, 2)));
  for (std::size_t i = 0; i < w.size(); ++i) w[i] = maxOpening * static_cast<double>(i) / static_cast<double>(w.size() - 1);
  std::vector<SofteningPoint> out;
  out.reserve(w.size());
  for (const double wi : w) out.push_back(atOpening(wi));
  return out;
}

double SofteningCurve::peakStress() const {
  // sigma(x) = f_t' x (E + E_p x^n) / (E x + E_p x^n) <= f_t': the peak is at x = 1; scanned
  // anyway so that the reported value is a measurement of the curve, not an assumption.
  double peak = 0.0;
  for (int i = 0; i <= 2000; ++i) peak = std::max(peak, uniaxialStress(law_, std::pow(10.0, -6.0 * i / 2000.0)));
  return peak;
}

}  // namespace ecm::calibration
