#pragma once
// What several cohesive tests share: a run's curve (peak, P at control 0.1 and 0.2 mm, the final
// energy-balance error), and the bar in uniaxial tension of the DEN concrete.
#include <algorithm>
#include <optional>
#include <string>

#include "cohesive/report.hpp"
#include "cohesive/scene.hpp"
#include "cohesive/solver.hpp"

namespace ecm::cohesive::test {

struct Curve {
  double peak = 0.0, at01 = 0.0, at02 = 0.0, finalBalance = 0.0;
};

inline Curve curveOf(const Scene& s) {
  const SolveResult r = solveControlled(buildModel(s), s.law, s.solver);
  Curve c;
  for (const StepRecord& h : r.history) c.peak = std::max(c.peak, h.load);
  c.at01 = loadAt(r.history, 0.1).value_or(0.0);
  c.at02 = loadAt(r.history, 0.2).value_or(0.0);
  c.finalBalance = r.history.back().balanceError;
  return c;
}

// A 50 x 10 x 10 mm bar (A = 100 mm^2), one element through its height, the DEN concrete. The
// band law's softening is steepest at its start, -E_p / h = -163.7 MPa/mm (docs/model.md), the
// bar's compliance L / E = 0.0016 mm/MPa is below 1/163.7 = 0.0061: no snap-back (nor for
// Hordijk's curve, steepest -110.7 MPa/mm).
inline Scene barScene(LawKind law, double finalDelta, double maxStep) {
  return parseScene(R"(
name: bar
problem: bar
thickness: 10
cell: 10
material: {youngs_modulus: 32000, poisson_ratio: 0.2, tensile_strength: 3.0, fracture_energy: 0.11}
law: band
band: {band_width: 0.05, softening_modulus: 8.184, softening_exponent: 0.128}
bar: {length: 50, height: 10}
control: {final: )" + std::to_string(finalDelta) + ", max_step: " + std::to_string(maxStep) + "}\n",
                    "bar.yaml", {std::nullopt, law});
}

}  // namespace ecm::cohesive::test
