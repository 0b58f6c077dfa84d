#pragma once
// The interface law of a run: ecm's band law or Hordijk's curve (an enum and a switch).
#include "cohesive/band_interface.hpp"
#include "cohesive/hordijk_interface.hpp"

namespace ecm::cohesive {

enum class LawKind { band, hordijk };

struct InterfaceLaw {
  LawKind kind = LawKind::hordijk;
  BandInterface band;        // when kind == band
  HordijkInterface hordijk;  // when kind == hordijk
  double tensileStrength() const { return kind == LawKind::band ? band.law.tensileStrength : hordijk.tensileStrength; }
  // The energy per area to complete failure: h int F dD, or the area under Hordijk's curve.
  double energyToFailure() const;
};

struct InterfaceState {
  BandState band;
  HordijkState hordijk;
};

inline InterfaceResponse updateInterface(const InterfaceLaw& law, InterfaceState& state, double jump) {
  return law.kind == LawKind::band ? updateBand(law.band, state.band, jump) : updateHordijk(law.hordijk, state.hordijk, jump);
}

inline double InterfaceLaw::energyToFailure() const {
  return kind == LawKind::band ? bandFractureEnergy(band) : hordijkArea(hordijk, hordijk.criticalOpening());
}

}  // namespace ecm::cohesive
