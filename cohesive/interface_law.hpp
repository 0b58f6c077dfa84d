#pragma once
// The interface law of a run: ecm's band law, Hordijk's curve or a table (an enum and a switch).
#include "cohesive/band_interface.hpp"
#include "cohesive/hordijk_interface.hpp"
#include "cohesive/table_interface.hpp"

namespace ecm::cohesive {

enum class LawKind { band, hordijk, table };

// The law's name in scenes and outputs: "band", "hordijk", "table".
inline const char* lawName(LawKind kind) {
  switch (kind) {
    case LawKind::band: return "band";
    case LawKind::hordijk: return "hordijk";
    case LawKind::table: return "table";
  }
  return "";
}

struct InterfaceLaw {
  LawKind kind = LawKind::hordijk;
  BandInterface band;        // when kind == band
  HordijkInterface hordijk;  // when kind == hordijk
  TableInterface table;      // when kind == table
  double tensileStrength() const;
  // The energy per area to complete failure: h int F dD, the area under Hordijk's curve, or the
  // area under the table's envelope to its last row (where a table need not have failed).
  double energyToFailure() const;
};

struct InterfaceState {
  BandState band;
  HordijkState hordijk;
  TableState table;
};

inline InterfaceResponse updateInterface(const InterfaceLaw& law, InterfaceState& state, double jump) {
  switch (law.kind) {
    case LawKind::band: return updateBand(law.band, state.band, jump);
    case LawKind::hordijk: return updateHordijk(law.hordijk, state.hordijk, jump);
    case LawKind::table: return updateTable(law.table, state.table, jump);
  }
  return {};
}

inline double InterfaceLaw::tensileStrength() const {
  switch (kind) {
    case LawKind::band: return band.law.tensileStrength;
    case LawKind::hordijk: return hordijk.tensileStrength;
    case LawKind::table: return table.tensileStrength();
  }
  return 0.0;
}

inline double InterfaceLaw::energyToFailure() const {
  switch (kind) {
    case LawKind::band: return bandFractureEnergy(band);
    case LawKind::hordijk: return hordijkArea(hordijk, hordijk.criticalOpening());
    case LawKind::table: return tableEnvelopeArea(table, 0.0, table.endOpening());
  }
  return 0.0;
}

}  // namespace ecm::cohesive
