#pragma once
// Fitting (E_p, n) to a target softening curve while dissipating G_F exactly: for each n the
// softening modulus is solved from G_F (solveSofteningModulus), so the fit is one-dimensional in
// n over (0, 0.5): a coarse scan, then Brent's minimiser (gsl_min_fminimizer_brent) around the
// best grid point.
#include "calibration/target_curve.hpp"
#include "material/damage_function.hpp"

namespace ecm::calibration {

// RMS over the target points of (sigma_model(w) - sigma_target(w)) / f_t', the model curve taken
// at exactly the target openings (SofteningCurve::stressesAtOpenings).
double fitResidual(const DamageLawParams& law, double width, const TargetCurve& target);

struct FitResult {
  double softeningExponent = 0.0;  // n
  double softeningModulus = 0.0;   // E_p (MPa)
  double residual = 0.0;           // fitResidual at (E_p, n)
  double fractureEnergy = 0.0;     // h int F dD at (E_p, n) (N/mm)
  double relativeError = 0.0;      // (that - G_F) / G_F
  int evaluations = 0;             // residual evaluations (each one E_p solve)
  bool atBound = false;            // the best n lies at the edge of the scanned interval
};

// `shape` gives E and f_t' (E_p and n are the unknowns).
FitResult fitSoftening(const DamageLawParams& shape, double fractureEnergy, double width, const TargetCurve& target);

}  // namespace ecm::calibration
