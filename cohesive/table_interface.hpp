#pragma once
// A traction-opening curve given as a table, so that the reference can carry the exact curve an
// enriched point of ecm follows in uniaxial stress (data/reference/beam-point-law.csv). Rows
// (w_i, T_i) from w_0 = 0, T_0 = f_t', linear between rows, behind an elastic stiffness K0: the
// envelope is min(K0 w, T(w)), the line K0 w up to the elastic limit w_e where it meets the
// table's first segment, the table after it. Irreversible like the band law: the largest opening
// reached, w_max, is the state; below it the interface follows the secant to the origin,
// envelope(w_max) w / w_max, in compression too (the band law's x E / h: a closing crack gets no
// stiffness back). An opening past the last row throws InterfaceLawError: the table is never
// extrapolated.
#include <cstddef>
#include <string>
#include <vector>

#include "cohesive/band_interface.hpp"  // InterfaceResponse, InterfaceLawError
#include "material/parameter_check.hpp"

namespace ecm::cohesive {

struct TableInterface {
  std::vector<double> opening;    // w_i (mm): 0 first, strictly increasing
  std::vector<double> traction;   // T_i (MPa): finite, >= 0; T_0 > 0 is f_t'
  double initialStiffness = 0.0;  // K0 (MPa/mm)
  std::string source;             // where the rows came from (a file), named in messages
  void validate() const;          // checkRows(), then checkStiffness()
  // Throws TableRowError naming the row: fewer than 2 rows, w_0 != 0, an opening not above the
  // one before, a traction negative or not finite, T_0 not > 0.
  void checkRows() const;
  // Throws ParameterError unless K0 > 0 and K0 w_i > T_i at every row i >= 1: then the line
  // K0 w meets the table once, inside its first segment, and stays above it after (both are
  // linear between rows), so the envelope min(K0 w, T) is the line and then the table.
  void checkStiffness() const;
  double tensileStrength() const { return traction.front(); }
  double endOpening() const { return opening.back(); }
  double elasticLimit() const;  // w_e = T_0 / (K0 - s_0), s_0 the first segment's slope
};

// A row that cannot be part of a table; `row` is 0-based (a reader maps it to a file line).
struct TableRowError : ParameterError {
  TableRowError(const std::string& what, std::size_t row) : ParameterError(what), row(row) {}
  std::size_t row;
};

struct TableState {
  double maxOpening = 0.0;  // w_max (mm)
};

// The envelope min(K0 w, T(w)) and its slope (the segment ahead at a row), 0 <= w <= the end.
double tableEnvelope(const TableInterface& p, double opening);
double tableEnvelopeSlope(const TableInterface& p, double opening);
// int_a^b envelope dw (exact: the pieces are linear), 0 <= a <= b <= the end.
double tableEnvelopeArea(const TableInterface& p, double a, double b);

InterfaceResponse updateTable(const TableInterface& p, TableState& state, double jump);

}  // namespace ecm::cohesive
