#pragma once
// The secant response of a cracked band: its elastic predictor as an affine map of the strain
// (docs/model.md, "The secant response of an unloading band"). With the band's damage frozen at
// x0, traction continuity (6) is linear in the jump, so the jump and the band's stress are affine
// in the macroscopic strain eps:
//   [u] = G eps + g,   a eps_L = B eps + b   (Eqs. (3), (6), (9) with a_L = x0 a).
// The maps depend on the band's fixed data (normal, onset strain, f) and on x0 alone, so they hold
// for a whole unloading episode: an explicit solver builds them once and then takes each
// unloading update as two 3x3 products instead of the predictor's solve. Plain data; built by
// TwoPhasePoint::secantResponse().
#include "material/band_state.hpp"
#include "material/voigt.hpp"

namespace ecm {

struct SecantResponse {
  // The band state the maps were built for (the key: a map that does not match is rebuilt).
  Vec2 crackNormal = Vec2::Zero();
  Voigt onsetStrain = Voigt::Zero();
  double volumeFraction = 0.0;
  double integrity = -1.0;                                      // x0; < 0: never built
  double threshold = 0.0;                                       // max(F(1), F(x0)): the band unloads while Y <= this, Eq. (12)
  Eigen::Matrix<double, 2, 3> jumpOfStrain = Eigen::Matrix<double, 2, 3>::Zero();  // G (mm)
  Vec2 jumpAtZeroStrain = Vec2::Zero();                         // g (mm)
  Tangent bandStressOfStrain = Tangent::Zero();                 // B (MPa)
  Voigt bandStressAtZeroStrain = Voigt::Zero();                 // b (MPa)

  // Whether the maps are those of band state b (its fixed data and its integrity, bit for bit).
  bool builtFor(const BandState& b) const {
    return integrity == b.integrity && volumeFraction == b.volumeFraction && crackNormal == b.crackNormal &&
           onsetStrain == b.onsetStrain;
  }
};

}  // namespace ecm
