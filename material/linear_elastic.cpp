#include "material/linear_elastic.hpp"

#include "material/parameter_check.hpp"

namespace ecm {

void ElasticParams::validate() const {
  requireInRange("youngs_modulus E (MPa)", youngsModulus, 0.0, 1e300);
  requireInRange("poisson_ratio nu", poissonRatio, -1.0, 0.5);
}

Tangent elasticStiffness(const ElasticParams& p) {
  const double e = p.youngsModulus, nu = p.poissonRatio;
  const double g = e / (2.0 * (1.0 + nu));
  Tangent a = Tangent::Zero();
  if (p.hypothesis == Hypothesis::PlaneStress) {
    const double c = e / (1.0 - nu * nu);
    a(0, 0) = a(1, 1) = c;
    a(0, 1) = a(1, 0) = c * nu;
  } else {
    const double c = e / ((1.0 + nu) * (1.0 - 2.0 * nu));
    a(0, 0) = a(1, 1) = c * (1.0 - nu);
    a(0, 1) = a(1, 0) = c * nu;
  }
  a(2, 2) = g;
  return a;
}

Tangent elasticCompliance(const ElasticParams& p) { return elasticStiffness(p).inverse(); }

double pWaveModulus(const ElasticParams& p) { return elasticStiffness(p)(0, 0); }

LinearElastic::LinearElastic(const ElasticParams& p) : stiffness_((p.validate(), elasticStiffness(p))) {}

UpdateResult LinearElastic::update(State& state, const Voigt& strainIncrement) const {
  state.strain += strainIncrement;
  UpdateResult r;
  r.stress = stiffness_ * state.strain;
  r.tangent = stiffness_;
  return r;
}

}  // namespace ecm
