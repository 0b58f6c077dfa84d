// The USL step in one pass over the particles (mpm/step.cpp): each point gathers from the
// updated grid, moves, takes its closed-form stress (Material::closedFormStress), locates its new stencil
// and scatters its mass, momentum and force into the next step's grid at once, while its fields
// are in cache. Separate transfers read every particle twice per step, and the step is bound
// by memory traffic, not arithmetic.
//
// Points whose stress is not closed-form (cracked, near onset, smeared) are deferred: they
// scatter after updateStresses. The particles are split into setup.threads fixed parts, one grid
// buffer each, summed in part order; within a part the sums take its closed-form points in
// index order, then its deferred points in index order. scatterState() builds exactly that
// grid from the particles and the last step's deferred list (FusedPass) on the first step, after
// a restart or when the particles changed between steps, so a rebuilt grid is bitwise the fused one.
#include <omp.h>

#include <algorithm>

#include "mpm/phases.hpp"
#include "mpm/transfer_kernels.hpp"

namespace ecm::mpm {

namespace {

using detail::kNoParticle;
using detail::ScatterTarget;

struct PartOutcome {
  std::size_t notFinite = kNoParticle;  // first particle with a non-finite velocity or position
  bool leftGrid = false;                // a particle's stencil left the grid
  detail::BaseSpan span;                // of the new stencils
};

struct TransferSetup {
  const Grid& grid;
  Vec2 invCell, halfWidth, gravity;
  bool withGravity;
};

TransferSetup setupOf(const Scene& scene, const Vec2& invCell, const Vec2& halfWidth) {
  return {scene.grid, invCell, halfWidth, scene.solver.gravity, scene.solver.gravity.squaredNorm() > 0.0};
}

template <ShapeFunction F>
PartOutcome gatherStressScatter(const TransferSetup& t, const GridFields& grid, Particles& p, std::size_t begin,
                                std::size_t end, double dt, double flip, const Material* materials,
                                ScatterTarget out, std::vector<std::uint32_t>& deferred) {
  const int nx = t.grid.nodesX();
  const double pic = 1.0 - flip;
  PartOutcome r;
  for (std::size_t i = begin; i < end; ++i) {
    Stencil s;
    expandStencil<F>(p.stencilAt[i], t.invCell, t.halfWidth, s);
    const detail::Gathered at = detail::gatherParticle<F, true>(s, nx, grid);
    const Vec2 vp = flip * (p.velocity[i] + at.velocityChange) + pic * at.velocity;
    const Vec2 x = p.position[i] + dt * at.velocity;
    p.velocity[i] = vp;
    p.position[i] = x;
    if (!(vp.allFinite() && x.allFinite())) {
      if (r.notFinite == kNoParticle) r.notFinite = i;
      continue;
    }
    const Voigt d = detail::strainIncrement(at, dt);
    Voigt sig;  // the closed-form stress, kept in registers for the scatter below
    const bool closedForm = materials[p.material[i]].closedFormStress(d, p.band[i] >= 0, p.strain[i], sig);
    if (!closedForm) {
      p.strainIncrement[i] = d;
      deferred.push_back(static_cast<std::uint32_t>(i));
    }
    StencilAt next;
    if (!locateStencil<F>(t.grid, t.invCell, t.halfWidth, x, next)) {
      r.leftGrid = true;  // reported by the next step's scatterState, as the separate transfers do
      if (closedForm) p.stress[i] = sig;
      continue;
    }
    p.stencilAt[i] = next;
    r.span.add(next.base);
    if (!closedForm) continue;
    expandStencil<F>(next, t.invCell, t.halfWidth, s);
    detail::scatterParticle<F, true, true>(s, nx, p.mass[i], vp, p.volume[i], sig, t.gravity, t.withGravity, out);
    p.stress[i] = sig;  // stored after its use: a reload right after the store stalls
  }
  return r;
}

// Scatters the particles of [begin, end) that are not in `listed` (sorted), then those listed;
// Locate: find their stencils first (a rebuild), else use the stored ones. Returns the first
// particle whose stencil left the grid.
template <ShapeFunction F, bool Locate>
std::size_t scatterInOrder(const TransferSetup& t, Particles& p, std::size_t begin, std::size_t end,
                           const std::uint32_t* listed, const std::uint32_t* listedEnd, ScatterTarget out,
                           detail::BaseSpan& span) {
  const int nx = t.grid.nodesX();
  const auto one = [&](std::size_t i) {
    if constexpr (Locate)
      if (!locateStencil<F>(t.grid, t.invCell, t.halfWidth, p.position[i], p.stencilAt[i])) return false;
    Stencil s;
    expandStencil<F>(p.stencilAt[i], t.invCell, t.halfWidth, s);
    detail::scatterParticle<F, true, true>(s, nx, p, i, t.gravity, t.withGravity, out);
    span.add(s.base);
    return true;
  };
  std::size_t bad = kNoParticle;
  const std::uint32_t* next = listed;
  for (std::size_t i = begin; i < end; ++i) {
    if (next != listedEnd && *next == i) {
      ++next;
      continue;
    }
    if (!one(i)) bad = std::min(bad, i);
  }
  for (const std::uint32_t* l = listed; l != listedEnd; ++l)
    if (!one(*l)) bad = std::min<std::size_t>(bad, *l);
  return bad;
}

using FusedFn = PartOutcome (*)(const TransferSetup&, const GridFields&, Particles&, std::size_t, std::size_t, double,
                                double, const Material*, ScatterTarget, std::vector<std::uint32_t>&);
using OrderedFn = std::size_t (*)(const TransferSetup&, Particles&, std::size_t, std::size_t, const std::uint32_t*,
                                  const std::uint32_t*, ScatterTarget, detail::BaseSpan&);

FusedFn fusedFor(ShapeFunction f) {
  return withShapeFunction(f, []<ShapeFunction F>() -> FusedFn { return gatherStressScatter<F>; });
}

template <bool Locate>
OrderedFn orderedFor(ShapeFunction f) {
  return withShapeFunction(f, []<ShapeFunction F>() -> OrderedFn { return scatterInOrder<F, Locate>; });
}

}  // namespace

void scatterState(const StepSetup& setup, long step, Particles& particles, GridFields& grid, ScatterBuffers& scatter,
                  const FusedPass& fused) {
  const Scene& scene = setup.scene;
  const TransferSetup tr = setupOf(scene, setup.invCell, setup.halfWidth);
  const OrderedFn fn = orderedFor<true>(scene.solver.shapeFunction);
  const std::size_t count = particles.size();
  const int nodes = scene.grid.nodeCount(), threads = setup.threads;
  const std::vector<std::uint32_t>& deferred = fused.deferred;
  std::size_t bad = kNoParticle;
  scatter.spans.resize(static_cast<std::size_t>(threads));
#pragma omp parallel for num_threads(threads) schedule(static, 1) reduction(min : bad)
  for (int t = 0; t < threads; ++t) {
    const ScatterTarget target = detail::targetOfPart(grid, scatter, t);
    detail::zeroTarget(target, nodes, true, true);
    const auto [b, e] = detail::partRange(count, t, threads);
    const std::uint32_t* end = deferred.data() + deferred.size();
    const std::uint32_t* first = std::lower_bound(deferred.data(), end, static_cast<std::uint32_t>(b));
    const std::uint32_t* last = std::lower_bound(first, end, static_cast<std::uint32_t>(e));
    detail::BaseSpan span;
    bad = std::min(bad, fn(tr, particles, b, e, first, last, target, span));
    scatter.spans[static_cast<std::size_t>(t)] = {span.lo, span.hi};
  }
  if (bad != kNoParticle) detail::throwLeftGrid(scene, step, particles, bad);
  detail::sumTouchedNodes(setup, grid, scatter);
}

bool gatherStressScatter(const StepSetup& setup, const Clock& clock, GridFields& grid, Particles& particles,
                         ScatterBuffers& scatter, FusedPass& fused) {
  const Scene& scene = setup.scene;
  const TransferSetup tr = setupOf(scene, setup.invCell, setup.halfWidth);
  const FusedFn fn = fusedFor(scene.solver.shapeFunction);
  const std::size_t count = particles.size();
  const int nodes = scene.grid.nodeCount(), threads = setup.threads;
  fused.deferredPerThread.resize(static_cast<std::size_t>(threads));
  std::size_t notFinite = kNoParticle;
  bool leftGrid = false;
  scatter.spans.resize(static_cast<std::size_t>(threads));
#pragma omp parallel for num_threads(threads) schedule(static, 1) reduction(min : notFinite) reduction(|| : leftGrid)
  for (int t = 0; t < threads; ++t) {
    const ScatterTarget target = detail::targetOfPart(grid, scatter, t);
    if (t == 0) {
      detail::zeroTarget(target, nodes, true, true);  // the grid itself: every node
    } else {  // a buffer: only where the last scatter left values
      const auto [lo, hi] = scatter.touched[static_cast<std::size_t>(t - 1)];
      detail::zeroNodes(target, lo, hi);
    }
    std::vector<std::uint32_t>& mine = fused.deferredPerThread[static_cast<std::size_t>(t)];
    mine.clear();
    const auto [b, e] = detail::partRange(count, t, threads);
    const PartOutcome o = fn(tr, grid, particles, b, e, clock.dt, scene.solver.flip, setup.materials.data(), target, mine);
    notFinite = std::min(notFinite, o.notFinite);
    leftGrid = leftGrid || o.leftGrid;
    scatter.spans[static_cast<std::size_t>(t)] = {o.span.lo, o.span.hi};
  }
  fused.deferred.clear();  // part t precedes part t + 1: the joined list is in index order
  for (const auto& mine : fused.deferredPerThread) fused.deferred.insert(fused.deferred.end(), mine.begin(), mine.end());
  if (notFinite != kNoParticle) detail::throwNotFinite(clock.step, particles, notFinite);
  return !leftGrid;
}

void scatterDeferred(const StepSetup& setup, Particles& particles, GridFields& grid, ScatterBuffers& scatter,
                     const FusedPass& fused) {
  const TransferSetup tr = setupOf(setup.scene, setup.invCell, setup.halfWidth);
  const OrderedFn fn = orderedFor<false>(setup.scene.solver.shapeFunction);
#pragma omp parallel for num_threads(setup.threads) schedule(static, 1)
  for (int t = 0; t < setup.threads; ++t) {
    const std::vector<std::uint32_t>& mine = fused.deferredPerThread[static_cast<std::size_t>(t)];
    auto& [lo, hi] = scatter.spans[static_cast<std::size_t>(t)];
    detail::BaseSpan span{lo, hi};
    fn(tr, particles, 0, 0, mine.data(), mine.data() + mine.size(), detail::targetOfPart(grid, scatter, t), span);
    lo = span.lo, hi = span.hi;
  }
  detail::sumTouchedNodes(setup, grid, scatter);
}

}  // namespace ecm::mpm
