// Particle-to-grid and grid-to-particle transfers. The scatter runs chunk by chunk in the fixed
// order of mpm/explicit/scatter_order.hpp (colour, chunk, particle index), straight into the grid: no
// per-thread copy of the grid, no locks, and every node sums its particles in the same order on
// any number of threads. The gathers only read the grid: any split of the particles gives the
// same bits.
#include <omp.h>

#include <algorithm>
#include <limits>
#include <sstream>

#include "mpm/core/errors.hpp"
#include "mpm/explicit/phases.hpp"
#include "mpm/explicit/transfer_kernels.hpp"

namespace ecm::mpm {

namespace {

using detail::kNoParticle;
using detail::ScatterTarget;

struct ScatterSetup {
  const Grid& grid;
  Vec2 invCell, halfWidth, gravity;
  const ScatterOrder& order;
};

// The particles of chunk c in index order; Stencils: located at their positions first, and the
// rows they start on measured. A particle whose stencil starts outside the chunk's plan does not
// scatter here (with Stencils it goes to `far`). Returns the first particle whose stencil left
// the grid.
template <ShapeFunction F, bool Stencils, bool MassMomentum, bool Forces>
std::size_t scatterChunk(const ScatterSetup& t, Particles& p, std::size_t c, ScatterTarget out, RowSpan& measured,
                         std::vector<std::uint32_t>& far) {
  const int nx = t.grid.nodesX();
  const bool withGravity = Forces && (t.gravity[0] != 0.0 || t.gravity[1] != 0.0);
  const auto [first, last] = t.order.range(c, p.size());
  const auto [lo, hi] = t.order.plannedBases(c);
  std::size_t bad = kNoParticle;
  BaseSpan span;
  for (std::size_t i = first; i < last; ++i) {
    if constexpr (Stencils) {
      if (!locateStencil<F>(t.grid, t.invCell, t.halfWidth, p.position[i], p.stencilAt[i])) {
        bad = std::min(bad, i);
        continue;
      }
      span.add(p.stencilAt[i].base);
    }
    const std::int32_t base = p.stencilAt[i].base;
    if (base < lo || base >= hi) {
      if constexpr (Stencils) far.push_back(static_cast<std::uint32_t>(i));
      continue;
    }
    Stencil s;
    expandStencil<F>(p.stencilAt[i], t.invCell, t.halfWidth, s);
    detail::scatterParticle<F, MassMomentum, Forces>(s, nx, p, i, t.gravity, withGravity, out);
  }
  if constexpr (Stencils) measured = span.rows(nx);
  return bad;
}

template <ShapeFunction F, bool MassMomentum, bool Forces, bool Mass = MassMomentum>
void scatterListed(const ScatterSetup& t, Particles& p, const std::vector<std::uint32_t>& listed, ScatterTarget out) {
  const int nx = t.grid.nodesX();
  const bool withGravity = Forces && (t.gravity[0] != 0.0 || t.gravity[1] != 0.0);
  for (const std::uint32_t i : listed) {
    Stencil s;
    expandStencil<F>(p.stencilAt[i], t.invCell, t.halfWidth, s);
    detail::scatterParticle<F, MassMomentum, Forces, Mass>(s, nx, p, i, t.gravity, withGravity, out);
  }
}

struct ScatterFns {
  std::size_t (*chunk)(const ScatterSetup&, Particles&, std::size_t, ScatterTarget, RowSpan&,
                       std::vector<std::uint32_t>&);
  void (*listed)(const ScatterSetup&, Particles&, const std::vector<std::uint32_t>&, ScatterTarget);
};

template <ShapeFunction F, bool MassMomentum, bool Forces>
ScatterFns scatterFns(bool stencils) {
  return {stencils ? scatterChunk<F, true, MassMomentum, Forces> : scatterChunk<F, false, MassMomentum, Forces>,
          scatterListed<F, MassMomentum, Forces>};
}

ScatterFns scatterFor(ShapeFunction f, unsigned what) {
  const bool st = what & kStencils, mm = what & kMassMomentum, fo = what & kForces;
  return withShapeFunction(f, [&]<ShapeFunction F>() -> ScatterFns {
    if (mm && fo) return scatterFns<F, true, true>(st);
    if (mm) return scatterFns<F, true, false>(st);
    if (fo) return scatterFns<F, false, true>(st);
    return scatterFns<F, false, false>(st);
  });
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
    if (bad == kNoParticle && !detail::finiteMotion(vp, p.position[i])) bad = i;
  }
  return bad;
}

// Strain increments and, where there is one, the closed-form stress; the other points are listed.
template <ShapeFunction F>
void strainStress(const Grid& g, const Vec2& invCell, const Vec2& halfWidth, const GridFields& grid, Particles& p,
                  std::size_t begin, std::size_t end, double dt, const Material* materials,
                  std::vector<std::uint32_t>& deferred) {
  const int nx = g.nodesX();
  for (std::size_t i = begin; i < end; ++i) {
    Stencil s;
    expandStencil<F>(p.stencilAt[i], invCell, halfWidth, s);
    const Voigt d = detail::strainIncrement(detail::gatherParticle<F, true>(s, nx, grid), dt);
    if (materials[p.material[i]].closedFormStress(d, p.band[i] >= 0, p.strain[i], p.stress[i])) continue;
    p.strainIncrement[i] = d;
    deferred.push_back(static_cast<std::uint32_t>(i));
  }
}

// MUSL: chunk c's grid-to-particle and the remap of its new velocities to the grid (momentum,
// with the step's stencils; the remapped mass would be the P2G's, bit for bit: the same stencils,
// masses and order of sums). Returns the first particle with a non-finite value.
template <ShapeFunction F>
std::size_t gatherRemapChunk(const ScatterSetup& t, const GridFields& grid, Particles& p, std::size_t c, double dt,
                             double flip, ScatterTarget out) {
  const int nx = t.grid.nodesX();
  const double pic = 1.0 - flip;
  const auto [first, last] = t.order.range(c, p.size());
  const auto [lo, hi] = t.order.plannedBases(c);
  std::size_t bad = kNoParticle;
  for (std::size_t i = first; i < last; ++i) {
    Stencil s;
    expandStencil<F>(p.stencilAt[i], t.invCell, t.halfWidth, s);
    const detail::Gathered at = detail::gatherParticle<F, false>(s, nx, grid);
    Vec2& vp = p.velocity[i];
    vp = flip * (vp + at.velocityChange) + pic * at.velocity;
    p.position[i] += dt * at.velocity;
    if (bad == kNoParticle && !detail::finiteMotion(vp, p.position[i])) bad = i;
    if (s.base < lo || s.base >= hi) continue;  // far: remapped after the colours
    detail::scatterParticle<F, true, false, false>(s, nx, p, i, t.gravity, false, out);
  }
  return bad;
}

using GatherFn = std::size_t (*)(const Grid&, const Vec2&, const Vec2&, const GridFields&, Particles&, std::size_t,
                                 std::size_t, double, double);

GatherFn gatherFor(ShapeFunction f, bool withStrain) {
  return withShapeFunction(f, [withStrain]<ShapeFunction F>() -> GatherFn { return withStrain ? gather<F, true> : gather<F, false>; });
}

}  // namespace

namespace detail {

void zeroScatterFields(int threads, GridFields& grid, bool massMomentum, bool forces, bool keepMass) {
  const auto nodes = static_cast<long>(grid.mass.size());
#pragma omp parallel for num_threads(threads) schedule(static)
  for (long n = 0; n < nodes; ++n) {
    const auto k = static_cast<std::size_t>(n);
    if (massMomentum) {
      if (!keepMass) grid.mass[k] = 0.0;
      grid.momentum[k].setZero();
    }
    if (forces) {
      grid.force[k].setZero();
      grid.externalForce[k].setZero();
    }
  }
}

void mergeSorted(std::vector<std::vector<std::uint32_t>>& perThread, std::vector<std::uint32_t>& into) {
  for (auto& v : perThread) {
    into.insert(into.end(), v.begin(), v.end());
    v.clear();
  }
  std::sort(into.begin(), into.end());
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

void particleToGrid(const StepSetup& setup, long step, Particles& particles, GridFields& grid, ScatterOrder& order,
                    unsigned what) {
  const Scene& scene = setup.scene;
  const Grid& g = scene.grid;
  const int threads = setup.threads;
  if (what & kStencils) {  // this step's plan, from where the stencils started in the last one
    planScatter(order, g.nodesY());
    order.far.clear();
  }
  detail::zeroScatterFields(threads, grid, what & kMassMomentum, what & kForces);
  const ScatterFns fn = scatterFor(scene.solver.shapeFunction, what);
  const ScatterSetup t{g, setup.invCell, setup.halfWidth, scene.solver.gravity, order};
  const ScatterTarget target = detail::targetOf(grid);
  std::vector<std::vector<std::uint32_t>> far(static_cast<std::size_t>(threads));
  std::vector<std::size_t> bad(static_cast<std::size_t>(threads), kNoParticle);
  std::vector<RowSpan>& measured = order.measured;
  forEachChunkByColour(order, threads, [&](std::size_t c, int th) {
    const auto k = static_cast<std::size_t>(th);
    bad[k] = std::min(bad[k], fn.chunk(t, particles, c, target, measured[c], far[k]));
  });
  const std::size_t first = *std::min_element(bad.begin(), bad.end());
  if (first != kNoParticle) detail::throwLeftGrid(scene, step, particles, first);
  if (what & kStencils) detail::mergeSorted(far, order.far);
  fn.listed(t, particles, order.far, target);  // after the colours, one at a time
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
    const std::size_t first = fn(scene.grid, setup.invCell, setup.halfWidth, grid, particles, b, e, clock.dt, scene.solver.explicitScheme.flip);
    if (first != kNoParticle) {
#pragma omp critical(ecm_mpm_failure)
      bad = std::min(bad, first);
    }
  }
  if (bad != kNoParticle) detail::throwNotFinite(clock.step, particles, bad);
}

void strainAndClosedFormStress(const StepSetup& setup, double dt, const GridFields& grid, Particles& particles,
                               std::vector<std::uint32_t>& deferred,
                               std::vector<std::vector<std::uint32_t>>& deferredPerThread) {
  const Scene& scene = setup.scene;
  const std::size_t count = particles.size();
  using Fn = void (*)(const Grid&, const Vec2&, const Vec2&, const GridFields&, Particles&, std::size_t, std::size_t,
                      double, const Material*, std::vector<std::uint32_t>&);
  const Fn fn = withShapeFunction(scene.solver.shapeFunction, []<ShapeFunction F>() -> Fn { return strainStress<F>; });
  deferredPerThread.resize(static_cast<std::size_t>(setup.threads));
#pragma omp parallel num_threads(setup.threads)
  {
    const int t = omp_get_thread_num();
    std::vector<std::uint32_t>& mine = deferredPerThread[static_cast<std::size_t>(t)];
    mine.clear();
    const auto [b, e] = detail::partRange(count, t, omp_get_num_threads());
    fn(scene.grid, setup.invCell, setup.halfWidth, grid, particles, b, e, dt, setup.materials.data(), mine);
  }
  deferred.clear();  // thread t's range precedes thread t + 1's: the joined list is in index order
  for (const auto& mine : deferredPerThread) deferred.insert(deferred.end(), mine.begin(), mine.end());
}

void gridToParticleAndRemap(const StepSetup& setup, const Clock& clock, GridFields& grid, Particles& particles,
                            const ScatterOrder& order) {
  const Scene& scene = setup.scene;
  const int threads = setup.threads;
  detail::zeroScatterFields(threads, grid, true, false, /*keepMass=*/true);
  const ScatterSetup t{scene.grid, setup.invCell, setup.halfWidth, scene.solver.gravity, order};
  const ScatterTarget target = detail::targetOf(grid);
  std::vector<std::size_t> bad(static_cast<std::size_t>(threads), kNoParticle);
  withShapeFunction(scene.solver.shapeFunction, [&]<ShapeFunction F>() {
    forEachChunkByColour(order, threads, [&](std::size_t c, int th) {
      const auto k = static_cast<std::size_t>(th);
      bad[k] = std::min(bad[k], gatherRemapChunk<F>(t, grid, particles, c, clock.dt, scene.solver.explicitScheme.flip, target));
    });
    scatterListed<F, true, false, false>(t, particles, order.far, target);  // after the colours, one at a time
  });
  const std::size_t first = *std::min_element(bad.begin(), bad.end());
  if (first != kNoParticle) detail::throwNotFinite(clock.step, particles, first);
}

}  // namespace ecm::mpm
