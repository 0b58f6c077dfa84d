#include "material/smeared_crack.hpp"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_roots.h>

#include <cmath>
#include <sstream>

#include "material/parameter_check.hpp"

namespace ecm {

UpdateResult SmearedCrack::update(State& state, const Voigt& increment) const {
  const Voigt eps = state.strain + increment;
  const BandResponse b = law_.evaluate(state.integrity, eps, true);
  UpdateResult r;
  r.stress = b.stress;
  r.tangent = b.tangent;
  r.dissipation = law_.dissipation(state.integrity, b.integrity);
  state.strain = eps;
  state.integrity = b.integrity;
  return r;
}

double criticalSmearedSize(double e, double ft, double gf) { return 2.0 * e * gf / (ft * ft); }

double regularisedSofteningModulus(const DamageLawParams& shape, double gf, double h) {
  requireInRange("fracture_energy GF (N/mm)", gf, 0.0, 1e300);
  requireInRange("effective_size H (mm)", h, 0.0, 1e300);
  const double hCrit = criticalSmearedSize(shape.youngsModulus, shape.tensileStrength, gf);
  if (h >= hCrit) {
    std::ostringstream msg;
    msg << "no crack-band regularisation exists for H = " << h << " mm >= H_crit = 2 E G_F / ft^2 = " << hCrit
        << " mm; the strength would have to drop to sqrt(2 E G_F / H) = "
        << std::sqrt(2.0 * shape.youngsModulus * gf / h) << " MPa";
    throw RegularisationError(msg.str(), hCrit, std::sqrt(2.0 * shape.youngsModulus * gf / h));
  }
  struct Ctx {
    DamageLawParams p;
    double target;
  } ctx{shape, gf / h};
  gsl_function fn;
  fn.function = [](double logEp, void* c) {
    auto* k = static_cast<Ctx*>(c);
    k->p.softeningModulus = std::exp(logEp);
    return std::log(dissipationToFailure(k->p) / k->target);
  };
  fn.params = &ctx;
  // Energy decreases with E_p; bracket in log E_p by expanding until the sign changes.
  double lo = std::log(shape.youngsModulus) - 20.0, hi = std::log(shape.youngsModulus) + 5.0;
  while (GSL_FN_EVAL(&fn, hi) > 0.0 && hi < 700.0) hi += 5.0;
  while (GSL_FN_EVAL(&fn, lo) < 0.0 && lo > -700.0) lo -= 5.0;
  gsl_root_fsolver* s = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
  gsl_root_fsolver_set(s, &fn, lo, hi);
  double root = 0.5 * (lo + hi);
  for (int it = 0; it < 200; ++it) {
    gsl_root_fsolver_iterate(s);
    root = gsl_root_fsolver_root(s);
    if (gsl_root_test_interval(gsl_root_fsolver_x_lower(s), gsl_root_fsolver_x_upper(s), 1e-14, 1e-13) == GSL_SUCCESS)
      break;
  }
  gsl_root_fsolver_free(s);
  return std::exp(root);
}

}  // namespace ecm
