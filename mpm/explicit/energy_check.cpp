// The explicit run's energy check (mpm/explicit/energy_check.hpp).
#include "mpm/explicit/energy_check.hpp"

#include <sstream>

#include "mpm/core/errors.hpp"

namespace ecm::mpm {

void checkDampingWork(const ExplicitSolver& solver, double initial) {
  const RunTotals& e = solver.state().totals;
  if (!dampingOutrunsInput(e, initial)) return;
  const Particles& p = solver.kinematics();
  std::size_t fastest = 0;
  for (std::size_t i = 1; i < p.size(); ++i)
    if (p.velocity[i].squaredNorm() > p.velocity[fastest].squaredNorm()) fastest = i;
  std::ostringstream msg;
  msg << "energy from nowhere at step " << solver.step() << ", t = " << solver.time() << " s: the damping's work, "
      << e.damping << " N mm, is beyond the energy put into the run, " << e.externalWork + initial
      << " N mm (external work " << e.externalWork << ", initial " << initial
      << "): a step went unstable (the fastest particle, " << fastest << ", at (" << p.position[fastest][0] << ", "
      << p.position[fastest][1] << ") mm, moves at " << p.velocity[fastest].norm() << " mm/s)";
  throw SimulationError(FailureKind::DampingWork, solver.step(), fastest, p.position[fastest], msg.str());
}

}  // namespace ecm::mpm
