// The rigid platens in the explicit grid phase (mpm/scene/platen.hpp, docs/validation.md): after
// the nodes' own update, each platen's nodes are made to move as one rigid body.
//
// With q = (u_x, u_y, theta) about the platen's reference and B_k the rigid map of node k
// (u_k = B_k q), the platen's generalized mass, momentum and force are
//   M = sum_k m_k B_k^T B_k,   g = sum_k B_k^T p_k,   F = sum_k B_k^T (f_int,k + f_ext,k).
// Its velocity at the step's end solves M V = g + dt (F + F_rig) with the prescribed components
// of V given (held 0, driven (u(t + dt) - u(t)) / dt), F_rig the rig's force on the free and
// force-driven ones (0 and the force history, local damping taken off as at any free node).
// The rig's force on the prescribed components is what that takes: (M V - g) / dt - F.
#include <array>
#include <cmath>

#include "mpm/explicit/phases.hpp"

namespace ecm::mpm {

namespace {

double sign(double v) { return static_cast<double>(static_cast<int>(v > 0.0) - static_cast<int>(v < 0.0)); }

}  // namespace

void applyPlatens(const StepSetup& setup, const Clock& clock, GridFields& grid, std::vector<PlatenState>& platens,
                  RunTotals* totals, bool withForces) {
  const Scene& scene = setup.scene;
  const double t = clock.time, dt = clock.dt, local = scene.solver.explicitScheme.damping.local;
  for (std::size_t i = 0; i < scene.platens.size(); ++i) {
    const Platen& platen = scene.platens[i];
    PlatenState& state = platens[i];
    Eigen::Matrix3d mass = Eigen::Matrix3d::Zero();
    Eigen::Vector3d momentum = Eigen::Vector3d::Zero(), force = Eigen::Vector3d::Zero();
    for (const std::int32_t node : state.nodes) {
      const auto n = static_cast<std::size_t>(node);
      const double m = grid.mass[n];
      if (!(m > 0.0)) continue;
      const Eigen::Matrix<double, 2, 3> b = rigidMap(scene.grid.nodePosition(node), state.reference);
      mass += m * b.transpose() * b;
      momentum += b.transpose() * grid.momentum[n];
      if (withForces) force += b.transpose() * (grid.force[n] + grid.externalForce[n]);
    }
    if (!(mass.trace() > 0.0)) continue;  // no material under the platen yet
    // The components: prescribed (their velocity known) or not (their force known).
    Eigen::Vector3d velocity = Eigen::Vector3d::Zero(), rig = Eigen::Vector3d::Zero();
    std::array<bool, 3> prescribed{};
    for (int d = 0; d < 3; ++d) {
      const PlatenDof& dof = platen.dof[static_cast<std::size_t>(d)];
      // A rotation that no node with mass can carry (all of the mass on one node: no inertia about
      // the centre of mass) is held this step.
      const double spin = mass(2, 2) - (mass(0, 2) * mass(0, 2) + mass(1, 2) * mass(1, 2)) / mass(0, 0);
      const bool unseen = d == kPlatenRotation && !(spin > 1e-12 * mass(2, 2));
      switch (dof.drive) {
        case PlatenDrive::Held: prescribed[d] = true; break;
        case PlatenDrive::Displacement:
          prescribed[d] = dof.drivenAt(t) || unseen;
          if (dof.drivenAt(t)) velocity[d] = (dof.history(t + dt) - dof.history(t)) / dt;
          break;
        case PlatenDrive::Force: rig[d] = withForces ? dof.history(t) : 0.0; [[fallthrough]];
        case PlatenDrive::Free: prescribed[d] = unseen; break;
      }
    }
    // Local damping of the unprescribed components, as at a free node.
    Eigen::Vector3d damping = Eigen::Vector3d::Zero();
    if (withForces && local > 0.0)
      for (int d = 0; d < 3; ++d)
        if (!prescribed[d]) damping[d] = local * std::abs(force[d] + rig[d]) * sign(state.velocity[d]);
    // M_ff V_f = g_f + dt (F + F_rig - damping)_f - M_fp V_p.
    int free[3], nf = 0;
    for (int d = 0; d < 3; ++d)
      if (!prescribed[d]) free[nf++] = d;
    if (nf > 0) {
      Eigen::MatrixXd mff(nf, nf);
      Eigen::VectorXd rhs(nf);
      for (int a = 0; a < nf; ++a) {
        rhs[a] = momentum[free[a]] + dt * (force[free[a]] + rig[free[a]] - damping[free[a]]);
        for (int d = 0; d < 3; ++d)
          if (prescribed[d]) rhs[a] -= mass(free[a], d) * velocity[d];
        for (int c = 0; c < nf; ++c) mff(a, c) = mass(free[a], free[c]);
      }
      const Eigen::VectorXd vf = mff.ldlt().solve(rhs);
      for (int a = 0; a < nf; ++a) velocity[free[a]] = vf[a];
    }
    // The nodes move with the platen; the loads' work at their new velocities.
    double loadWork = 0.0;
    for (const std::int32_t node : state.nodes) {
      const auto n = static_cast<std::size_t>(node);
      const double m = grid.mass[n];
      if (!(m > 0.0)) continue;
      const Vec2 v = rigidMap(scene.grid.nodePosition(node), state.reference) * velocity;
      const Vec2 vOld = grid.momentum[n] * (1.0 / m);
      if (withForces) loadWork += dt * grid.externalForce[n].dot(v - grid.velocity[n]);  // corrects updateGrid's sum
      grid.velocity[n] = v;
      grid.velocityChange[n] = v - vOld;
    }
    state.velocity = velocity;
    if (!totals) continue;
    // What the rig puts on the specimen: on a prescribed component what holds it there, on the
    // others the force history (the damping is not the rig's).
    const Eigen::Vector3d onSpecimen = (mass * velocity - momentum) / dt - force + damping;
    for (int d = 0; d < 3; ++d) state.force[d] = prescribed[d] ? onSpecimen[d] : rig[d];
    totals->externalWork += dt * state.force.dot(velocity) + loadWork;
    totals->damping += dt * damping.dot(velocity);
    state.displacement += dt * velocity;
  }
}

}  // namespace ecm::mpm
