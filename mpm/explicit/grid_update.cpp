// The grid phase: nodal velocities from momentum, the explicit update with damping, the
// velocity conditions with their reactions, and the loads.
#include <cmath>

#include "mpm/core/ordered_sum.hpp"
#include "mpm/explicit/phases.hpp"
#include "mpm/core/shape_function.hpp"

namespace ecm::mpm {

namespace {

// Without a branch: the sign of a vibrating node's velocity is not predictable.
double sign(double v) { return static_cast<double>(static_cast<int>(v > 0.0) - static_cast<int>(v < 0.0)); }

// Prescribed velocity of a component over [t, t + dt], or NaN when the component is free.
double prescribed(const ComponentCondition& c, double t, double dt) {
  switch (c.kind) {
    case Prescribed::Free: return NAN;
    case Prescribed::Fixed: return 0.0;
    case Prescribed::Velocity: return c.history(t + dt);
    case Prescribed::Displacement: return (c.history(t + dt) - c.history(t)) / dt;
  }
  return NAN;
}

// The velocity conditions at the nodes: prescribed components take their velocity over
// [t, t + dt]. Given the totals, the reactions are recorded and their work added to them, and the
// loads' work, summed by updateGrid with the free velocities, is corrected to the prescribed ones
// (withLoads: the grid carries loads or gravity).
void applyVelocityConditions(const StepSetup& setup, const Clock& clock, GridFields& grid,
                             std::vector<ConditionState>& conditions, RunTotals* totals, bool withLoads) {
  const Scene& scene = setup.scene;
  const double t = clock.time, dt = clock.dt;
  for (std::size_t c = 0; c < scene.conditions.size(); ++c) {
    const NodeCondition& cond = scene.conditions[c];
    ConditionState& state = conditions[c];
    const double vx = prescribed(cond.component[0], t, dt), vy = prescribed(cond.component[1], t, dt);
    const double scale = cond.field ? cond.field->scale(t + dt) : 0.0;
    Vec2 reaction = Vec2::Zero();
    double work = 0.0;
    for (const std::int32_t node : state.nodes) {
      const auto n = static_cast<std::size_t>(node);
      const double m = grid.mass[n];
      if (!(m > 0.0)) continue;
      const Vec2 vOld = grid.momentum[n] * (1.0 / m);  // v = p (1 / m), as the other grid loops take it
      Vec2 vp(vx, vy);
      if (cond.field) vp = scale * cond.field->gradient * (scene.grid.nodePosition(node) - cond.field->origin);
      for (int d = 0; d < 2; ++d) {
        if (std::isnan(vp[d])) continue;
        if (totals) {
          const double r = m * (vp[d] - vOld[d]) / dt - (grid.force[n][d] + grid.externalForce[n][d]);
          reaction[d] += r;
          work += dt * r * vp[d];
          if (withLoads) work += dt * grid.externalForce[n][d] * (vp[d] - grid.velocity[n][d]);
        }
        grid.velocity[n][d] = vp[d];
        grid.velocityChange[n][d] = vp[d] - vOld[d];
      }
    }
    if (!totals) continue;
    state.reaction = reaction;
    totals->externalWork += work;
    for (int d = 0; d < 2; ++d) {
      const ComponentCondition& k = cond.component[static_cast<std::size_t>(d)];
      if (cond.field) continue;
      if (k.kind == Prescribed::Displacement) state.displacement[d] = k.history(t + dt);
      if (k.kind == Prescribed::Velocity) state.displacement[d] += dt * (d == 0 ? vx : vy);
    }
  }
}

// A node that a particle has only just reached (a free surface moving into empty cells) carries a
// sliver of a node's mass but, with linear shape functions, the full gradient: its own frequency
// outruns the step and the particle's stress and the node's velocity ring up within a few steps.
// A node whose mass is below kLeastShare of a full node's (rho h_x h_y t, the lightest material)
// takes kLeastShare of a full node's mass for its acceleration (docs/model.md, "Nodes with little
// mass"). Measured at CFL 0.6: a rising block held with 0.15 and blew up with 0.1, the fine
// L-panel ran with 0.1. Corner, edge and inner nodes of a body hold 0.25, 0.5 and 1 of a full
// node's mass: none is touched (tests/mpm/mass_scaling_test.cpp), and runs without such nodes
// are bitwise unchanged.
constexpr double kLeastShare = 0.2;

}  // namespace

void updateGrid(const StepSetup& setup, const Clock& clock, GridFields& grid, std::vector<ConditionState>& conditions,
                RunTotals& totals) {
  const Scene& scene = setup.scene;
  const int nodes = scene.grid.nodeCount();
  const double dt = clock.dt, viscous = scene.solver.explicitScheme.damping.viscous, local = scene.solver.explicitScheme.damping.local;
  const bool withLoads = !scene.loads.empty() || scene.solver.gravity.squaredNorm() > 0.0;
  // One pass over the nodes: the update, the damping forces' work and the loads' work (at the
  // free velocities; applyVelocityConditions corrects the prescribed components).
  // USL with linear shape functions only: USF and MUSL strain the particles with velocities that
  // are mass-weighted means of particle velocities (bounded whatever a node's mass), and uGIMP's
  // and the B-splines' weights and gradients fade together at the edge of their support.
  const bool exposed = scene.solver.shapeFunction == ShapeFunction::Linear && scene.solver.explicitScheme.scheme == UpdateScheme::USL;
  const double least = exposed ? kLeastShare * setup.fullNodeMass : 0.0;
  const Eigen::Vector3d sums = orderedSum(setup.threads, nodes, Eigen::Vector3d(Eigen::Vector3d::Zero()), [&](long node) -> Eigen::Vector3d {
    const auto n = static_cast<std::size_t>(node);
    const double m = grid.mass[n];
    if (!(m > 0.0)) {
      grid.velocity[n].setZero();
      grid.velocityChange[n].setZero();
      return Eigen::Vector3d::Zero();
    }
    const double invMass = 1.0 / m;  // one division per node, not three: the loop's cost
    const bool scaled = m < least;
    const double accelerationInvMass = scaled ? 1.0 / least : invMass;
    const Vec2 v = grid.momentum[n] * invMass;
    const Vec2 f = grid.force[n] + grid.externalForce[n];
    Vec2 fd = f;
    if (viscous > 0.0) fd -= viscous * m * v;
    if (local > 0.0) fd -= local * Vec2(std::abs(f[0]) * sign(v[0]), std::abs(f[1]) * sign(v[1]));
    if (const std::uint8_t c = setup.constrained[n]) {  // prescribed components are not damped
      if (c & 1) fd[0] = f[0];
      if (c & 2) fd[1] = f[1];
    }
    const Vec2 vNew = v + (dt * accelerationInvMass) * fd;
    grid.velocity[n] = vNew;
    grid.velocityChange[n] = vNew - v;
    return Eigen::Vector3d(dt * (f - fd).dot(vNew), withLoads ? dt * grid.externalForce[n].dot(vNew) : 0.0, scaled ? 1.0 : 0.0);
  });
  totals.damping += sums[0];
  totals.externalWork += sums[1];
  totals.massScaled += static_cast<long>(sums[2]);
  applyVelocityConditions(setup, clock, grid, conditions, &totals, withLoads);
}

void gridVelocities(const StepSetup& setup, const Clock& clock, GridFields& grid,
                    std::vector<ConditionState>& conditions) {
  const int nodes = setup.scene.grid.nodeCount();
#pragma omp parallel for num_threads(setup.threads) schedule(static)
  for (int node = 0; node < nodes; ++node) {
    const auto n = static_cast<std::size_t>(node);
    const double m = grid.mass[n];
    grid.velocity[n] = m > 0.0 ? Vec2(grid.momentum[n] * (1.0 / m)) : Vec2::Zero();
  }
  applyVelocityConditions(setup, clock, grid, conditions, nullptr, false);
}

void addLoads(const StepSetup& setup, double time, const Particles& particles, GridFields& grid,
              std::vector<LoadState>& loads) {
  const Scene& scene = setup.scene;
  const int nx = scene.grid.nodesX();
  const int s = supportSize(scene.solver.shapeFunction);
  for (std::size_t l = 0; l < scene.loads.size(); ++l) {
    const Load& load = scene.loads[l];
    LoadState& state = loads[l];
    state.applied = load.force * load.history(time);
    const Vec2 each = state.applied / static_cast<double>(state.members.size());
    for (const std::int32_t member : state.members) {
      if (load.target == LoadTarget::Nodes) {
        grid.externalForce[static_cast<std::size_t>(member)] += each;
        continue;
      }
      Stencil st;
      expandStencil(scene.solver.shapeFunction, particles.stencilAt[static_cast<std::size_t>(member)], setup.invCell,
                    setup.halfWidth, st);
      for (int j = 0; j < s; ++j)
        for (int k = 0; k < s; ++k)
          grid.externalForce[static_cast<std::size_t>(st.base + j * nx + k)] += st.wx[k] * st.wy[j] * each;
    }
  }
}

}  // namespace ecm::mpm
