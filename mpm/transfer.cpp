// Particle-to-grid and grid-to-particle transfers. Each thread scatters a fixed contiguous range
// of particles into its own grid buffer (thread 0 straight into the grid); the buffers are then
// summed node by node in thread order. No locks; a node only sees a different summation order
// when particles of two ranges share it.
#include <omp.h>

#include <algorithm>
#include <limits>
#include <sstream>

#include "mpm/solver.hpp"
#include "mpm/transfer_kernels.hpp"

namespace ecm::mpm {

namespace {

using detail::kNoParticle;
using detail::ScatterTarget;

template <ShapeFunction F, bool Stencils, bool MassMomentum, bool Forces>
std::size_t scatter(const Grid& g, const Vec2& invCell, const Vec2& halfWidth, Particles& p, std::size_t begin,
                    std::size_t end, const Vec2& gravity, ScatterTarget out) {
  const int nx = g.nodesX();
  const bool withGravity = Forces && (gravity[0] != 0.0 || gravity[1] != 0.0);
  for (std::size_t i = begin; i < end; ++i) {
    if constexpr (Stencils)
      if (!locateStencil<F>(g, invCell, halfWidth, p.position[i], p.stencilAt[i])) return i;
    Stencil s;
    expandStencil<F>(p.stencilAt[i], invCell, halfWidth, s);
    detail::scatterParticle<F, MassMomentum, Forces>(s, nx, p, i, gravity, withGravity, out);
  }
  return kNoParticle;
}

using ScatterFn = std::size_t (*)(const Grid&, const Vec2&, const Vec2&, Particles&, std::size_t, std::size_t,
                                  const Vec2&, ScatterTarget);

template <ShapeFunction F>
ScatterFn scatterFor(unsigned what) {
  const bool st = what & kStencils, mm = what & kMassMomentum, fo = what & kForces;
  if (st && mm && fo) return scatter<F, true, true, true>;
  if (st && mm) return scatter<F, true, true, false>;
  if (mm && fo) return scatter<F, false, true, true>;
  if (mm) return scatter<F, false, true, false>;
  if (st && fo) return scatter<F, true, false, true>;
  if (fo) return scatter<F, false, false, true>;
  return scatter<F, true, false, false>;
}

ScatterFn scatterFor(ShapeFunction f, unsigned what) {
  return withShapeFunction(f, [what]<ShapeFunction F>() { return scatterFor<F>(what); });
}

template <ShapeFunction F, bool WithStrain>
std::size_t gather(const Grid& g, const Vec2& invCell, const Vec2& halfWidth, const GridFields& grid, Particles& p,
                   std::size_t begin, std::size_t end, double dt, double flip) {
  const int nx = g.nodesX();
  const double pic = 1.0 - flip;
  std::size_t bad = kNoParticle;
  for (std::size_t i = begin; i < end; ++i) {
    Stencil s;
    expandStencil<F>(p.stencilAt[i], invCell, halfWidth, s);
    const detail::Gathered at = detail::gatherParticle<F, WithStrain>(s, nx, grid);
    Vec2& vp = p.velocity[i];
    vp = flip * (vp + at.velocityChange) + pic * at.velocity;
    p.position[i] += dt * at.velocity;
    if constexpr (WithStrain) p.strainIncrement[i] = detail::strainIncrement(at, dt);
    if (bad == kNoParticle && !(vp.allFinite() && p.position[i].allFinite())) bad = i;
  }
  return bad;
}

template <ShapeFunction F>
void strainIncrements(const Grid& g, const Vec2& invCell, const Vec2& halfWidth, const GridFields& grid, Particles& p,
                      std::size_t begin, std::size_t end, double dt) {
  const int nx = g.nodesX();
  for (std::size_t i = begin; i < end; ++i) {
    Stencil s;
    expandStencil<F>(p.stencilAt[i], invCell, halfWidth, s);
    p.strainIncrement[i] = detail::strainIncrement(detail::gatherParticle<F, true>(s, nx, grid), dt);
  }
}

using GatherFn = std::size_t (*)(const Grid&, const Vec2&, const Vec2&, const GridFields&, Particles&, std::size_t,
                                 std::size_t, double, double);
using StrainFn = void (*)(const Grid&, const Vec2&, const Vec2&, const GridFields&, Particles&, std::size_t, std::size_t,
                          double);

GatherFn gatherFor(ShapeFunction f, bool withStrain) {
  return withShapeFunction(f, [withStrain]<ShapeFunction F>() -> GatherFn { return withStrain ? gather<F, true> : gather<F, false>; });
}

}  // namespace

ScatterTarget Solver::part(int t) {
  return t == 0 ? detail::targetOf(grid_) : detail::targetOf(scratch_[static_cast<std::size_t>(t - 1)]);
}

void Solver::particleToGrid(unsigned what) {
  const ScatterFn fn = scatterFor(scene_.solver.shapeFunction, what);
  const int nodes = scene_.grid.nodeCount();
  const std::size_t count = particles_.size();
  std::size_t bad = kNoParticle;
  int used = 1;
#pragma omp parallel num_threads(threads_)
  {
    const int t = omp_get_thread_num(), n = omp_get_num_threads();
#pragma omp single
    used = n;
    const ScatterTarget target = part(t);
    detail::zeroTarget(target, nodes, what & kMassMomentum, what & kForces);
    const auto [b, e] = detail::partRange(count, t, n);
    const std::size_t mine = fn(scene_.grid, invCell_, halfWidth_, particles_, b, e, scene_.solver.gravity, target);
    if (mine != kNoParticle) {
#pragma omp critical(ecm_mpm_failure)
      bad = std::min(bad, mine);
    }
  }
  if (bad != kNoParticle) throwLeftGrid(bad);
  sumScatterBuffers(what, used);
  touched_.assign(scratch_.size(), {0, nodes});  // the buffers hold values anywhere
  if (what & kForces) addLoads();
}

void Solver::gridToParticle(bool withStrainIncrements) {
  const std::size_t count = particles_.size();
  const GatherFn fn = gatherFor(scene_.solver.shapeFunction, withStrainIncrements);
  std::size_t bad = kNoParticle;
#pragma omp parallel num_threads(threads_)
  {
    const auto [b, e] = detail::partRange(count, omp_get_thread_num(), omp_get_num_threads());
    const std::size_t first = fn(scene_.grid, invCell_, halfWidth_, grid_, particles_, b, e, dt_, scene_.solver.flip);
    if (first != kNoParticle) {
#pragma omp critical(ecm_mpm_failure)
      bad = std::min(bad, first);
    }
  }
  if (bad != kNoParticle) throwNotFinite(bad);
}

void Solver::sumScatterBuffers(unsigned what, int parts) {
  for (int t = 1; t < parts; ++t) addScatterBuffer(t, what, 0, scene_.grid.nodeCount());
}

// Buffer t added into the grid over nodes [lo, hi). Buffer by buffer, node by node: every node
// sums the buffers in part order.
void Solver::addScatterBuffer(int t, unsigned what, int lo, int hi) {
  const GridAccumulator& a = scratch_[static_cast<std::size_t>(t - 1)];
#pragma omp parallel for num_threads(threads_) schedule(static)
  for (int node = lo; node < hi; ++node) {
    const auto k = static_cast<std::size_t>(node);
    if (what & kMassMomentum) {
      grid_.mass[k] += a.mass[k];
      grid_.momentum[k] += a.momentum[k];
    }
    if (what & kForces) {
      grid_.force[k] += a.force[k];
      grid_.externalForce[k] += a.externalForce[k];
    }
  }
}

void Solver::computeStrainIncrements() {
  const std::size_t count = particles_.size();
  const StrainFn fn = withShapeFunction(scene_.solver.shapeFunction, []<ShapeFunction F>() -> StrainFn { return strainIncrements<F>; });
#pragma omp parallel num_threads(threads_)
  {
    const auto [b, e] = detail::partRange(count, omp_get_thread_num(), omp_get_num_threads());
    fn(scene_.grid, invCell_, halfWidth_, grid_, particles_, b, e, dt_);
  }
}

void Solver::throwNotFinite(std::size_t p) const {
  std::ostringstream msg;
  msg << "step " << step_ + 1 << ": particle " << p << " has a non-finite velocity or position (velocity ("
      << particles_.velocity[p][0] << ", " << particles_.velocity[p][1] << ") mm/s)";
  throw SimulationError(FailureKind::NotFinite, step_ + 1, p, particles_.position[p], msg.str());
}

void Solver::throwLeftGrid(std::size_t p) const {
  const Vec2& x = particles_.position[p];
  std::ostringstream msg;
  const Vec2 hi = scene_.grid.origin + scene_.grid.extent();
  msg << "step " << step_ << ": particle " << p << " at (" << x[0] << ", " << x[1] << ") mm left the grid ["
      << scene_.grid.origin[0] << ", " << hi[0] << "] x [" << scene_.grid.origin[1] << ", " << hi[1] << "] mm";
  if (scene_.solver.shapeFunction != ShapeFunction::Linear) msg << " (or its " << toString(scene_.solver.shapeFunction) << " support did)";
  throw SimulationError(FailureKind::LeftGrid, step_, p, x, msg.str());
}

}  // namespace ecm::mpm
