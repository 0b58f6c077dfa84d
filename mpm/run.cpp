// A whole run of a scene (mpm/run.hpp): the solver's stepper in the one run loop.
#include "mpm/run.hpp"

#include "mpm/explicit_run.hpp"
#include "mpm/implicit_run.hpp"
#include "mpm/run_loop.hpp"

namespace ecm::mpm {

RunResult runScene(const Scene& scene, const RunOptions& options) {
  const std::unique_ptr<Stepper> stepper =
      scene.solver.implicit ? implicitStepper(scene, options) : explicitStepper(scene, options);
  return runLoop(scene, options, *stepper);
}

}  // namespace ecm::mpm
