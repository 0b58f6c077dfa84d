#pragma once
// Isotropic linear elasticity in 2D (plane stress or plane strain).
#include "material/update_result.hpp"

namespace ecm {

struct ElasticParams {
  double youngsModulus = 0.0;  // E (MPa)
  double poissonRatio = 0.0;   // nu (-)
  Hypothesis hypothesis = Hypothesis::PlaneStress;
  void validate() const;  // throws ParameterError
};

Tangent elasticStiffness(const ElasticParams& p);  // a : strain -> stress (Voigt, engineering shear)
Tangent elasticCompliance(const ElasticParams& p); // a^-1 (in-plane; sigma_zz is not part of it)
// P-wave modulus a_11 (MPa): sets the elastic wave speed sqrt(a_11 / density).
double pWaveModulus(const ElasticParams& p);

class LinearElastic {
 public:
  struct State {
    Voigt strain = Voigt::Zero();
  };

  explicit LinearElastic(const ElasticParams& p);
  UpdateResult update(State& state, const Voigt& strainIncrement) const;
  const Tangent& stiffness() const { return stiffness_; }

 private:
  Tangent stiffness_;
};

}  // namespace ecm
