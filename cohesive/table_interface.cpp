#include "cohesive/table_interface.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "material/parameter_check.hpp"

namespace ecm::cohesive {

namespace {

// The segment [w_k, w_k+1] that holds w (the one ahead at a row; the last at the end).
std::size_t segment(const TableInterface& p, double w) {
  const auto above = std::upper_bound(p.opening.begin(), p.opening.end(), w);
  const std::size_t k = above == p.opening.begin() ? 0 : static_cast<std::size_t>(above - p.opening.begin()) - 1;
  return std::min(k, p.opening.size() - 2);
}

double segmentSlope(const TableInterface& p, std::size_t k) {
  return (p.traction[k + 1] - p.traction[k]) / (p.opening[k + 1] - p.opening[k]);
}

// The table's linear interpolation T(w).
double interpolated(const TableInterface& p, double w) {
  const std::size_t k = segment(p, w);
  return p.traction[k] + segmentSlope(p, k) * (w - p.opening[k]);
}

// int_a^b T(w) dw of the interpolation, trapezoids between rows (exact), a <= b.
double tableArea(const TableInterface& p, double a, double b) {
  const std::size_t i = segment(p, a), j = segment(p, b);
  if (i == j) return 0.5 * (interpolated(p, a) + interpolated(p, b)) * (b - a);
  double area = 0.5 * (interpolated(p, a) + p.traction[i + 1]) * (p.opening[i + 1] - a);
  for (std::size_t k = i + 1; k < j; ++k) area += 0.5 * (p.traction[k] + p.traction[k + 1]) * (p.opening[k + 1] - p.opening[k]);
  return area + 0.5 * (p.traction[j] + interpolated(p, b)) * (b - p.opening[j]);
}

// The energy dissipated while w_max grows from wOld to wNew: D(w) = int_0^w envelope - envelope(w) w / 2
// (the work along the envelope minus what the secant stores), zero up to w_e; with
// K0 w_e = T(w_e) the elastic triangle cancels, D(wNew) - D(wOld) = int_a^wNew T - T(wNew) wNew / 2
// + T(a) a / 2, a = max(wOld, w_e).
double dissipated(const TableInterface& p, double wOld, double wNew) {
  const double a = std::max(wOld, p.elasticLimit());
  if (wNew <= a) return 0.0;
  return tableArea(p, a, wNew) - 0.5 * interpolated(p, wNew) * wNew + 0.5 * interpolated(p, a) * a;
}

}  // namespace

void TableInterface::checkRows() const {
  if (opening.size() != traction.size()) throw TableRowError("the table's columns differ in length", 0);
  if (opening.size() < 2)
    throw TableRowError("the table needs at least 2 rows, it has " + std::to_string(opening.size()), opening.empty() ? 0 : opening.size() - 1);
  if (opening[0] != 0.0) throw TableRowError("the first row's opening must be 0 (where the crack starts at f_t'), not " + numberText(opening[0], 10) + " mm", 0);
  for (std::size_t k = 0; k < opening.size(); ++k) {
    if (!std::isfinite(opening[k])) throw TableRowError("opening " + numberText(opening[k], 10) + " is not finite", k);
    if (k > 0 && !(opening[k] > opening[k - 1]))
      throw TableRowError("opening " + numberText(opening[k], 10) + " mm is not above the previous row's " + numberText(opening[k - 1], 10) +
                              " mm: the openings must increase strictly",
                          k);
    if (!(std::isfinite(traction[k]) && traction[k] >= 0.0))
      throw TableRowError("traction " + numberText(traction[k], 10) + " MPa at opening " + numberText(opening[k], 10) + " mm must be finite and >= 0", k);
  }
  if (!(traction[0] > 0.0)) throw TableRowError("the first row's traction is the tensile strength f_t' and must be > 0", 0);
}

void TableInterface::checkStiffness() const {
  requireInRange("initial stiffness K0", initialStiffness, 0.0, INFINITY);
  for (std::size_t k = 1; k < opening.size(); ++k)
    if (!(initialStiffness * opening[k] > traction[k]))
      throw ParameterError("initial stiffness K0 = " + numberText(initialStiffness, 10) + " MPa/mm is too low: the line K0 w must stay above the table from its second row on, but at opening " +
                           numberText(opening[k], 10) + " mm K0 w = " + numberText(initialStiffness * opening[k], 10) + " MPa against the table's " + numberText(traction[k], 10) +
                           " MPa");
}

void TableInterface::validate() const {
  checkRows();
  checkStiffness();
}

double TableInterface::elasticLimit() const {
  return traction[0] / (initialStiffness - (traction[1] - traction[0]) / opening[1]);
}

double tableEnvelope(const TableInterface& p, double w) {
  return w <= p.elasticLimit() ? p.initialStiffness * w : interpolated(p, w);
}

double tableEnvelopeSlope(const TableInterface& p, double w) {
  return w < p.elasticLimit() ? p.initialStiffness : segmentSlope(p, segment(p, w));
}

double tableEnvelopeArea(const TableInterface& p, double a, double b) {
  const double we = p.elasticLimit();
  double area = 0.0;
  if (a < we) area += 0.5 * p.initialStiffness * (std::min(b, we) * std::min(b, we) - a * a);
  if (b > we) area += tableArea(p, std::max(a, we), b);
  return area;
}

InterfaceResponse updateTable(const TableInterface& p, TableState& state, double jump) {
  const double wOld = state.maxOpening;
  InterfaceResponse r;
  if (jump > wOld) {  // loading on the envelope
    if (jump > p.endOpening())
      throw InterfaceLawError("opening " + numberText(jump, 10) + " mm is past the end of the traction-opening table" +
                              (p.source.empty() ? std::string() : " " + p.source) + " (its last row is at " + numberText(p.endOpening(), 10) +
                              " mm): the table law does not extrapolate, extend the table");
    r.traction = tableEnvelope(p, jump);
    r.tangent = tableEnvelopeSlope(p, jump);
    r.dissipation = dissipated(p, wOld, jump);
    r.stored = 0.5 * r.traction * jump;
    state.maxOpening = jump;
    return r;
  }
  // Below w_max, or closed: the secant to the origin (K0 while w_max is on the elastic line).
  const double secant = wOld <= p.elasticLimit() ? p.initialStiffness : tableEnvelope(p, wOld) / wOld;
  r.traction = secant * jump;
  r.tangent = secant;
  r.stored = 0.5 * secant * jump * jump;
  return r;
}

}  // namespace ecm::cohesive
