#pragma once
// Target softening curves (w, sigma) for the fit: the Hordijk curve (Cornelissen, Hordijk and
// Reinhardt 1986) or measured points (read from a CSV file by calibration/target_csv.hpp).
#include <string>
#include <vector>

namespace ecm::calibration {

struct TargetCurve {
  std::string source;          // "hordijk" or the CSV path
  std::vector<double> opening; // w (mm), strictly increasing, >= 0
  std::vector<double> stress;  // sigma (MPa)
};

// Hordijk's critical opening w_c = 5.14 G_F / f_t' (mm): sigma = 0 beyond it.
double hordijkCriticalOpening(double tensileStrength, double fractureEnergy);
// sigma/f_t' = (1 + (c1 w/w_c)^3) exp(-c2 w/w_c) - (w/w_c)(1 + c1^3) exp(-c2), c1 = 3, c2 = 6.93.
double hordijkStress(double opening, double tensileStrength, double fractureEnergy);
// `count` points w_i = i w_c / count, i = 1..count.
TargetCurve hordijkCurve(double tensileStrength, double fractureEnergy, int count = 100);
// The gnuplot expression of the Hordijk curve in x = w, for plots.
std::string hordijkGnuplot(double tensileStrength, double fractureEnergy);

// The same checks for a curve built in code (CalibrationError).
void validateTarget(const TargetCurve& target);

}  // namespace ecm::calibration
