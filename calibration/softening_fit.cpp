#include "calibration/softening_fit.hpp"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_min.h>

#include <cmath>
#include <stdexcept>

#include "calibration/fracture_energy.hpp"
#include "calibration/softening_curve.hpp"

namespace ecm::calibration {

double fitResidual(const DamageLawParams& law, double width, const TargetCurve& target) {
  const std::vector<double> model = SofteningCurve(law, width).stressesAtOpenings(target.opening);
  double sum = 0.0;
  for (std::size_t i = 0; i < model.size(); ++i) {
    const double d = (model[i] - target.stress[i]) / law.tensileStrength;
    sum += d * d;
  }
  return std::sqrt(sum / static_cast<double>(model.size()));
}

namespace {

// The scanned interval of n: n -> 0.5 needs E_p -> infinity, n -> 0 a vanishing tail.
constexpr double kMinExponent = 0.005, kMaxExponent = 0.495;
constexpr int kScanPoints = 10;

struct Objective {
  DamageLawParams shape;
  double fractureEnergy;
  double width;
  const TargetCurve* target;
  int evaluations = 0;

  DamageLawParams law(double n) const {
    DamageLawParams p = shape;
    p.softeningExponent = n;
    p.softeningModulus = solveSofteningModulus(p, fractureEnergy, width).softeningModulus;
    return p;
  }
  double operator()(double n) {
    ++evaluations;
    return fitResidual(law(n), width, *target);
  }
};

}  // namespace

FitResult fitSoftening(const DamageLawParams& shape, double fractureEnergy, double width, const TargetCurve& target) {
  validateTarget(target);
  Objective f{shape, fractureEnergy, width, &target};

  // Coarse scan for a bracket (the residual need not be unimodal over all of (0, 0.5)).
  std::vector<double> n(kScanPoints), r(kScanPoints);
  int best = 0;
  for (int i = 0; i < kScanPoints; ++i) {
    n[i] = kMinExponent + (kMaxExponent - kMinExponent) * i / (kScanPoints - 1);
    r[i] = f(n[i]);
    if (r[i] < r[best]) best = i;
  }
  FitResult out;
  double nBest = n[best];
  if (best == 0 || best == kScanPoints - 1) {
    out.atBound = true;
  } else {
    struct Ctx {
      Objective* f;
    } ctx{&f};
    gsl_function fn;
    fn.function = [](double x, void* c) { return (*static_cast<Ctx*>(c)->f)(x); };
    fn.params = &ctx;
    gsl_min_fminimizer* m = gsl_min_fminimizer_alloc(gsl_min_fminimizer_brent);
    gsl_error_handler_t* old = gsl_set_error_handler_off();
    int status = gsl_min_fminimizer_set_with_values(m, &fn, n[best], r[best], n[best - 1], r[best - 1], n[best + 1],
                                                    r[best + 1]);
    for (int it = 0; it < 100 && status == GSL_SUCCESS; ++it) {
      status = gsl_min_fminimizer_iterate(m);
      if (gsl_min_test_interval(gsl_min_fminimizer_x_lower(m), gsl_min_fminimizer_x_upper(m), 1e-7, 0.0) == GSL_SUCCESS)
        break;
    }
    nBest = gsl_min_fminimizer_x_minimum(m);
    gsl_set_error_handler(old);
    gsl_min_fminimizer_free(m);
    if (status != GSL_SUCCESS) throw std::runtime_error(std::string("softening fit: ") + gsl_strerror(status));
  }
  out.softeningExponent = nBest;
  DamageLawParams p = shape;
  p.softeningExponent = nBest;
  const SofteningModulusSolution s = solveSofteningModulus(p, fractureEnergy, width);
  p.softeningModulus = s.softeningModulus;
  out.softeningModulus = s.softeningModulus;
  out.fractureEnergy = s.fractureEnergy;
  out.relativeError = s.relativeError;
  out.residual = fitResidual(p, width, target);
  out.evaluations = f.evaluations + 1;
  return out;
}

}  // namespace ecm::calibration
