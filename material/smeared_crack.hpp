#pragma once
// The smeared crack (crack band) model for comparison: the band's damage law of Eqs. (11)-(13)
// applied to the whole point strain. Regularised when E_p is chosen so that G_F/H is dissipated
// per unit volume (Bazant's crack band), unregularised when the band's E_p is used as is.
#include "material/band_damage_law.hpp"

namespace ecm {

class SmearedCrack {
 public:
  struct State {
    Voigt strain = Voigt::Zero();
    double integrity = 1.0;  // x = 1 - D
    double damage() const { return 1.0 - integrity; }
  };

  explicit SmearedCrack(const BandDamageParams& p) : law_(p) {}
  UpdateResult update(State& state, const Voigt& strainIncrement) const;
  const BandDamageLaw& law() const { return law_; }

 private:
  BandDamageLaw law_;
};

// Thrown when no E_p of the F(D) form can dissipate G_F/H per unit volume.
struct RegularisationError : std::domain_error {
  double criticalSize;       // H_crit = 2 E G_F / f_t'^2 (mm)
  double requiredStrength;   // sqrt(2 E G_F / H) (MPa): the strength reduction that would be needed
  RegularisationError(const std::string& what, double hCrit, double ft)
      : std::domain_error(what), criticalSize(hCrit), requiredStrength(ft) {}
};

// H_crit = 2 E G_F / f_t'^2: the minimum energy per volume of the law is the elastic energy at
// peak, f_t'^2/(2E), reached as E_p -> infinity (docs/model.md, identities).
double criticalSmearedSize(double youngsModulus, double tensileStrength, double fractureEnergy);

// E_p such that int_0^1 F dD = G_F / H for the given n (Brent on log E_p, rel. 1e-12).
// Throws RegularisationError for H >= H_crit.
double regularisedSofteningModulus(const DamageLawParams& shape, double fractureEnergy, double effectiveSize);

}  // namespace ecm
