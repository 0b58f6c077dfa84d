#pragma once
// Newton under control of a linear displacement functional c . u (CMOD, an edge displacement):
// the load factor lambda is an unknown, and each iteration solves the bordered system
//   [ K_t   -f_ref ] [du     ]   [ -R                  ]
//   [ c^T    0     ] [dlambda] = [ target - c . u      ]
// The bulk is linear elastic, so only the interface nodes' diagonal entries of the matrix change:
// it is factorised once at rest (Eigen's SparseLU) and each iteration's system is solved exactly
// from those factors by Woodbury's identity (a dense system of the interface's size).
// Adaptive steps: halve on a failed step, grow after easy ones (and limit P's change per step).
#include <Eigen/Core>

#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "cohesive/interface_law.hpp"
#include "cohesive/model.hpp"

namespace ecm::cohesive {

struct SolverSettings {
  double finalControl = 0.3;   // control value to reach (mm)
  double firstStep = 1e-3;     // first control increment (mm)
  double maxStep = 1e-3;       // largest control increment (mm)
  double minStep = 1e-8;       // below this a failing step ends the run
  double maxLoadStep = 0.0;    // largest change of P (N, full specimen) per step; 0: no limit
  double tolerance = 1e-10;    // residual, relative to the force scale (see solver.cpp)
  int maxIterations = 25;
};

// One converged step; energies of the full specimen (the half model's times two).
struct StepRecord {
  int step = 0;
  double control = 0.0;           // c . u (mm)
  double load = 0.0;              // P (N), full specimen
  double loadDisplacement = 0.0;  // the load's own displacement (mm)
  double externalWork = 0.0;      // int P d u_load, trapezoidal (N mm)
  double bulkEnergy = 0.0;        // elastic energy of the bulk (N mm)
  double interfaceEnergy = 0.0;   // stored in the interface (N mm)
  double dissipation = 0.0;       // dissipated in the interface (N mm)
  double balanceError = 0.0;      // |W - U_bulk - U_int - D| / W (0 while W = 0)
  int iterations = 0;
};

struct InterfaceSample {
  double position = 0.0;  // along the ligament (mm)
  double opening = 0.0;   // jump (mm)
  double traction = 0.0;  // MPa
  double dissipation = 0.0;  // per area, accumulated (N/mm)
};

struct SolveResult {
  std::vector<StepRecord> history;
  std::vector<InterfaceSample> ligament;  // at the last converged step
  Eigen::VectorXd displacement;           // equation space, last converged step
};

// A step that failed at the smallest increment; what converged before it is in `partial`.
struct SolveFailure : std::runtime_error {
  SolveFailure(const std::string& what, SolveResult partial) : std::runtime_error(what), partial(std::move(partial)) {}
  SolveResult partial;
};

// Runs from rest to settings.finalControl. `onStep` sees each converged step (also step 0 at
// rest), e.g. to write it to disk at once. Throws SolveFailure with the step and control value.
SolveResult solveControlled(const HalfModel& model, const InterfaceLaw& law, const SolverSettings& settings,
                            const std::function<void(const StepRecord&)>& onStep = {});

}  // namespace ecm::cohesive
