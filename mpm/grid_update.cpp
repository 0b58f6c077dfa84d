// The grid phase: nodal velocities from momentum, the explicit update with damping, the
// velocity conditions with their reactions, and the loads.
#include <cmath>

#include "mpm/ordered_sum.hpp"
#include "mpm/solver.hpp"

namespace ecm::mpm {

namespace {

double sign(double v) { return v > 0.0 ? 1.0 : (v < 0.0 ? -1.0 : 0.0); }

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

}  // namespace

void Solver::updateGrid() {
  const int nodes = scene_.grid.nodeCount();
  const double dt = dt_, viscous = scene_.solver.damping.viscous, local = scene_.solver.damping.local;
  damping_ += orderedSum(threads_, nodes, 0.0, [&](long node) {
    const auto n = static_cast<std::size_t>(node);
    const double m = grid_.mass[n];
    if (!(m > 0.0)) {
      grid_.velocity[n].setZero();
      grid_.velocityChange[n].setZero();
      return 0.0;
    }
    const Vec2 v = grid_.momentum[n] / m;
    const Vec2 f = grid_.force[n] + grid_.externalForce[n];
    Vec2 fd = f;
    if (viscous > 0.0) fd -= viscous * m * v;
    if (local > 0.0) fd -= local * Vec2(std::abs(f[0]) * sign(v[0]), std::abs(f[1]) * sign(v[1]));
    if (const std::uint8_t c = constrained_[n]) {  // prescribed components are not damped
      if (c & 1) fd[0] = f[0];
      if (c & 2) fd[1] = f[1];
    }
    const Vec2 vNew = v + dt / m * fd;
    grid_.velocity[n] = vNew;
    grid_.velocityChange[n] = vNew - v;
    return dt * (f - fd).dot(vNew);  // work of the damping forces
  });
  applyVelocityConditions(true);
  if (!scene_.loads.empty() || scene_.solver.gravity.squaredNorm() > 0.0) {
    const double work = orderedSum(threads_, nodes, 0.0, [&](long node) {
      return grid_.externalForce[static_cast<std::size_t>(node)].dot(grid_.velocity[static_cast<std::size_t>(node)]);
    });
    externalWork_ += dt * work;
  }
}

void Solver::gridVelocities() {
  const int nodes = scene_.grid.nodeCount();
#pragma omp parallel for num_threads(threads_) schedule(static)
  for (int node = 0; node < nodes; ++node) {
    const auto n = static_cast<std::size_t>(node);
    const double m = grid_.mass[n];
    grid_.velocity[n] = m > 0.0 ? Vec2(grid_.momentum[n] / m) : Vec2::Zero();
  }
  applyVelocityConditions(false);
}

void Solver::applyVelocityConditions(bool reactions) {
  const double t = time_, dt = dt_;
  for (std::size_t c = 0; c < scene_.conditions.size(); ++c) {
    const NodeCondition& cond = scene_.conditions[c];
    ConditionState& state = conditions_[c];
    const double vx = prescribed(cond.component[0], t, dt), vy = prescribed(cond.component[1], t, dt);
    const double scale = cond.field ? cond.field->scale(t + dt) : 0.0;
    Vec2 reaction = Vec2::Zero();
    double work = 0.0;
    for (const std::int32_t node : state.nodes) {
      const auto n = static_cast<std::size_t>(node);
      const double m = grid_.mass[n];
      if (!(m > 0.0)) continue;
      const Vec2 vOld = grid_.momentum[n] / m;
      Vec2 vp(vx, vy);
      if (cond.field) vp = scale * cond.field->gradient * (scene_.grid.nodePosition(node) - cond.field->origin);
      for (int d = 0; d < 2; ++d) {
        if (std::isnan(vp[d])) continue;
        if (reactions) {
          const double r = m * (vp[d] - vOld[d]) / dt - (grid_.force[n][d] + grid_.externalForce[n][d]);
          reaction[d] += r;
          work += dt * r * vp[d];
        }
        grid_.velocity[n][d] = vp[d];
        grid_.velocityChange[n][d] = vp[d] - vOld[d];
      }
    }
    if (!reactions) continue;
    state.reaction = reaction;
    externalWork_ += work;
    for (int d = 0; d < 2; ++d) {
      const ComponentCondition& k = cond.component[static_cast<std::size_t>(d)];
      if (cond.field) continue;
      if (k.kind == Prescribed::Displacement) state.displacement[d] = k.history(t + dt);
      if (k.kind == Prescribed::Velocity) state.displacement[d] += dt * (d == 0 ? vx : vy);
    }
  }
}

void Solver::addLoads() {
  const int nx = scene_.grid.nodesX();
  const int s = supportSize(scene_.solver.shapeFunction);
  for (std::size_t l = 0; l < scene_.loads.size(); ++l) {
    const Load& load = scene_.loads[l];
    LoadState& state = loads_[l];
    state.applied = load.force * load.history(time_);
    const Vec2 each = state.applied / static_cast<double>(state.members.size());
    for (const std::int32_t member : state.members) {
      if (load.target == LoadTarget::Nodes) {
        grid_.externalForce[static_cast<std::size_t>(member)] += each;
        continue;
      }
      Stencil st;
      expandStencil(scene_.solver.shapeFunction, particles_.stencilAt[static_cast<std::size_t>(member)], invCell_, halfWidth_, st);
      for (int j = 0; j < s; ++j)
        for (int k = 0; k < s; ++k)
          grid_.externalForce[static_cast<std::size_t>(st.base + j * nx + k)] += st.wx[k] * st.wy[j] * each;
    }
  }
}

}  // namespace ecm::mpm
