// Particle-to-grid and grid-to-particle transfers. Each thread scatters a fixed contiguous range
// of particles into its own grid buffer (thread 0 straight into the grid); the buffers are then
// summed node by node in thread order. No locks; a node only sees a different summation order
// when particles of two ranges share it.
#include <omp.h>

#include <algorithm>
#include <limits>
#include <sstream>

#include "mpm/errors.hpp"
#include "mpm/phases.hpp"
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

ScatterTarget part(GridFields& grid, ScatterBuffers& scatter, int t) {
  return t == 0 ? detail::targetOf(grid) : detail::targetOf(scatter.buffers[static_cast<std::size_t>(t - 1)]);
}

// Buffer t added into the grid over nodes [lo, hi). Buffer by buffer, node by node: every node
// sums the buffers in part order.
void addScatterBuffer(int threads, const GridAccumulator& a, GridFields& grid, unsigned what, int lo, int hi) {
#pragma omp parallel for num_threads(threads) schedule(static)
  for (int node = lo; node < hi; ++node) {
    const auto k = static_cast<std::size_t>(node);
    if (what & kMassMomentum) {
      grid.mass[k] += a.mass[k];
      grid.momentum[k] += a.momentum[k];
    }
    if (what & kForces) {
      grid.force[k] += a.force[k];
      grid.externalForce[k] += a.externalForce[k];
    }
  }
}

}  // namespace

namespace detail {

ScatterTarget targetOfPart(GridFields& grid, ScatterBuffers& scatter, int t) { return part(grid, scatter, t); }

void sumTouchedNodes(const StepSetup& setup, GridFields& grid, ScatterBuffers& scatter) {
  const Grid& g = setup.scene.grid;
  const int nx = g.nodesX(), nodes = g.nodeCount();
  const int s = supportSize(setup.scene.solver.shapeFunction);
  const int reach = (s - 1) * nx + s;
  for (int t = 1; t < setup.threads; ++t) {
    const auto [lo, hi] = scatter.spans[static_cast<std::size_t>(t)];
    const std::pair<int, int> range = lo > hi ? std::pair{0, 0} : std::pair{lo, std::min(nodes, hi + reach)};
    scatter.touched[static_cast<std::size_t>(t - 1)] = range;
    addScatterBuffer(setup.threads, scatter.buffers[static_cast<std::size_t>(t - 1)], grid, kMassMomentum | kForces,
                     range.first, range.second);
  }
}

void throwNotFinite(long step, const Particles& particles, std::size_t p) {
  std::ostringstream msg;
  msg << "step " << step + 1 << ": particle " << p << " has a non-finite velocity or position (velocity ("
      << particles.velocity[p][0] << ", " << particles.velocity[p][1] << ") mm/s)";
  throw SimulationError(FailureKind::NotFinite, step + 1, p, particles.position[p], msg.str());
}

void throwLeftGrid(const Scene& scene, long step, const Particles& particles, std::size_t p) {
  const Vec2& x = particles.position[p];
  std::ostringstream msg;
  const Vec2 hi = scene.grid.origin + scene.grid.extent();
  msg << "step " << step << ": particle " << p << " at (" << x[0] << ", " << x[1] << ") mm left the grid ["
      << scene.grid.origin[0] << ", " << hi[0] << "] x [" << scene.grid.origin[1] << ", " << hi[1] << "] mm";
  if (scene.solver.shapeFunction != ShapeFunction::Linear) msg << " (or its " << toString(scene.solver.shapeFunction) << " support did)";
  throw SimulationError(FailureKind::LeftGrid, step, p, x, msg.str());
}

}  // namespace detail

void particleToGrid(const StepSetup& setup, long step, Particles& particles, GridFields& grid, ScatterBuffers& scatter,
                    unsigned what) {
  const Scene& scene = setup.scene;
  const ScatterFn fn = scatterFor(scene.solver.shapeFunction, what);
  const int nodes = scene.grid.nodeCount();
  const std::size_t count = particles.size();
  std::size_t bad = kNoParticle;
  int used = 1;
#pragma omp parallel num_threads(setup.threads)
  {
    const int t = omp_get_thread_num(), n = omp_get_num_threads();
#pragma omp single
    used = n;
    const ScatterTarget target = part(grid, scatter, t);
    detail::zeroTarget(target, nodes, what & kMassMomentum, what & kForces);
    const auto [b, e] = detail::partRange(count, t, n);
    const std::size_t mine = fn(scene.grid, setup.invCell, setup.halfWidth, particles, b, e, scene.solver.gravity, target);
    if (mine != kNoParticle) {
#pragma omp critical(ecm_mpm_failure)
      bad = std::min(bad, mine);
    }
  }
  if (bad != kNoParticle) detail::throwLeftGrid(scene, step, particles, bad);
  for (int t = 1; t < used; ++t)
    addScatterBuffer(setup.threads, scatter.buffers[static_cast<std::size_t>(t - 1)], grid, what, 0, nodes);
  scatter.touched.assign(scatter.buffers.size(), {0, nodes});  // the buffers hold values anywhere
}

void gridToParticle(const StepSetup& setup, const Clock& clock, const GridFields& grid, Particles& particles,
                    bool withStrainIncrements) {
  const Scene& scene = setup.scene;
  const std::size_t count = particles.size();
  const GatherFn fn = gatherFor(scene.solver.shapeFunction, withStrainIncrements);
  std::size_t bad = kNoParticle;
#pragma omp parallel num_threads(setup.threads)
  {
    const auto [b, e] = detail::partRange(count, omp_get_thread_num(), omp_get_num_threads());
    const std::size_t first = fn(scene.grid, setup.invCell, setup.halfWidth, grid, particles, b, e, clock.dt, scene.solver.flip);
    if (first != kNoParticle) {
#pragma omp critical(ecm_mpm_failure)
      bad = std::min(bad, first);
    }
  }
  if (bad != kNoParticle) detail::throwNotFinite(clock.step, particles, bad);
}

void computeStrainIncrements(const StepSetup& setup, double dt, const GridFields& grid, Particles& particles) {
  const Scene& scene = setup.scene;
  const std::size_t count = particles.size();
  const StrainFn fn = withShapeFunction(scene.solver.shapeFunction, []<ShapeFunction F>() -> StrainFn { return strainIncrements<F>; });
#pragma omp parallel num_threads(setup.threads)
  {
    const auto [b, e] = detail::partRange(count, omp_get_thread_num(), omp_get_num_threads());
    fn(scene.grid, setup.invCell, setup.halfWidth, grid, particles, b, e, dt);
  }
}

}  // namespace ecm::mpm
