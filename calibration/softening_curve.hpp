#pragma once
// The law's traction-opening curve in uniaxial tension, parameterised by the integrity x = 1 - D
// on the monotonic branch:
//   sigma(x) = uniaxialStress(law, x) = x sqrt(2 E F(x))      (Eq. (11) with Y = F, Eq. (13))
//   eps_L(x) = sigma / (x E)                                 (band strain, Eq. (11))
//   w(x)     = width (eps_L - sigma / E)                      (inelastic opening)
// The opening w is the band's strain beyond the elastic strain sigma/E, times the band width h:
// the crack opening of a cohesive-crack description, 0 at peak (x = 1) and growing without
// bound as x -> 0. With this w, int_0^inf sigma dw = h int_0^1 F dD = G_F. For the crack-band
// (smeared) calibration the width is the element size H.
#include <vector>

#include "material/damage_function.hpp"

namespace ecm::calibration {

struct SofteningPoint {
  double opening = 0.0;     // w (mm)
  double stress = 0.0;      // sigma (MPa)
  double damage = 0.0;      // D = 1 - x
  double bandStrain = 0.0;  // eps_L (-)
};

class SofteningCurve {
 public:
  SofteningCurve(const DamageLawParams& law, double width);

  SofteningPoint at(double integrity) const;
  // The inverse maps (Brent in log x; w decreases and sigma increases with x).
  double integrityAtOpening(double opening) const;
  double integrityAtStress(double stress) const;  // on the softening branch, 0 < stress <= f_t'
  SofteningPoint atOpening(double opening) const { return at(integrityAtOpening(opening)); }
  // Opening at which sigma has dropped to `fraction` of f_t' (0 < fraction <= 1).
  double openingAtStressFraction(double fraction) const;

  // Stresses at increasing openings (the work horse of the fit: each root brackets the next).
  std::vector<double> stressesAtOpenings(const std::vector<double>& openings) const;
  // `count` points evenly spaced in w over [0, maxOpening].
  std::vector<SofteningPoint> sample(double maxOpening, int count) const;

  double peakStress() const;  // max sigma over the curve (f_t' at x = 1 for Eq. (13))
  const DamageLawParams& law() const { return law_; }
  double width() const { return width_; }

 private:
  DamageLawParams law_;
  double width_;
  double opening(double integrity) const;
  // Root of g(log x) = 0 bracketed in [logLo, logHi] (Brent, |d log x| <= 1e-13).
  template <class G>
  double solveLogIntegrity(const G& g, double logLo, double logHi) const;
};

}  // namespace ecm::calibration
