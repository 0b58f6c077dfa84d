// The USL step in one pass over the particles (mpm/explicit/step.cpp): each point gathers from the
// updated grid, moves, takes its closed-form stress (Material::closedFormStress), locates its new
// stencil and scatters its mass, momentum and force into the next step's grid at once (a block
// of 32 points at a time), while its fields are in cache. Separate transfers read every particle
// twice per step, and the step is bound by memory traffic, not arithmetic.
//
// The pass runs chunk by chunk in the scatter order of mpm/explicit/scatter_order.hpp, planned at its
// start. Points whose stress is not closed-form (cracked, near onset, smeared) are deferred:
// they take Material::update after the pass and then scatter, chunk by chunk in the same colours
// and groups; a point whose new stencil is outside its chunk's plan (far) scatters last, alone.
// So every node sums, in this fixed order: the closed-form points (colour, chunk, index), the
// deferred points (colour, chunk, index), the far points (index), on any number of threads.
// scatterState() rebuilds exactly that grid from the particles, the plan and the deferred list
// (first step, restart, particles changed between steps), so a rebuilt grid is bitwise the
// fused one.
#include <omp.h>

#include <algorithm>

#include "mpm/explicit/phases.hpp"
#include "mpm/explicit/transfer_kernels.hpp"

namespace ecm::mpm {

namespace {

using detail::kNoParticle;
using detail::ScatterTarget;

struct ChunkOutcome {
  std::size_t notFinite = kNoParticle;  // first particle with a non-finite velocity or position
  bool leftGrid = false;                // a particle's stencil left the grid
};

struct TransferSetup {
  const Grid& grid;
  Vec2 invCell, halfWidth, gravity;
  bool withGravity;
  const ScatterOrder& order;
};

TransferSetup setupOf(const StepSetup& s, const ScatterOrder& order) {
  return {s.scene.grid, s.invCell, s.halfWidth, s.scene.solver.gravity, s.scene.solver.gravity.squaredNorm() > 0.0, order};
}

// The particle arrays the fused pass reads and writes, as plain pointers taken once per chunk:
// through the vectors, every store into one array made the compiler load the others' data
// pointers again (it cannot tell that a store of a double does not move a vector).
struct PassArrays {
  Vec2* __restrict position;
  Vec2* __restrict velocity;
  const double* __restrict mass;    // (not read where the material's points share it: `shared`)
  const double* __restrict volume;
  Voigt* __restrict strain;
  Voigt* __restrict stress;  // written for the far points and those that left the grid only
  Voigt* __restrict strainIncrement;
  const std::uint8_t* __restrict material;
  const std::int32_t* __restrict band;
  StencilAt* __restrict stencilAt;
};

PassArrays arraysOf(Particles& p) {
  return {p.position.data(), p.velocity.data(), p.mass.data(),   p.volume.data(), p.strain.data(),
          p.stress.data(),   p.strainIncrement.data(), p.material.data(), p.band.data(), p.stencilAt.data()};
}

template <ShapeFunction F>
ChunkOutcome gatherStressScatter(const TransferSetup& t, const GridFields& grid, Particles& particles, std::size_t c,
                                 double dt, double flip, const Material* materials, const SharedMassVolume* shared,
                                 ScatterTarget out, RowSpan& measured, std::vector<std::uint32_t>& deferred,
                                 std::vector<std::uint32_t>& far) {
  const int nx = t.grid.nodesX();
  const double pic = 1.0 - flip;
  const auto [first, last] = t.order.range(c, particles.size());
  const auto [lo, hi] = t.order.plannedBases(c);
  const PassArrays p = arraysOf(particles);
  const detail::GatherSource from = detail::sourceOf(grid);
  // Local copies, for the same reason: loaded once, not after every store.
  const Grid geometry = t.grid;
  const Vec2 invCell = t.invCell, halfWidth = t.halfWidth, gravity = t.gravity;
  const bool withGravity = t.withGravity;
  ChunkOutcome r;
  BaseSpan span;
  // A block of particles at a time: first each one's gather, move and closed-form stress, then
  // the block's scatter. The gathers of a block do not wait on each other's scatters, so the
  // processor overlaps them; the scatter still adds to every node in particle order.
  constexpr std::size_t kBlock = 32;
  Voigt sig[kBlock];             // the closed-form stresses, for the scatter (not reloaded after the store)
  std::uint32_t scatters[kBlock];// the block's particles that scatter now, in index order
  for (std::size_t b = first; b < last; b += kBlock) {
    const std::size_t end = std::min(last, b + kBlock);
    std::size_t count = 0;
    for (std::size_t i = b; i < end; ++i) {
      Stencil s;
      expandStencil<F>(p.stencilAt[i], invCell, halfWidth, s);
      const detail::Gathered at = detail::gatherParticle<F, true>(s, nx, from);
      const Vec2 vp = flip * (p.velocity[i] + at.velocityChange) + pic * at.velocity;
      const Vec2 x = p.position[i] + dt * at.velocity;
      p.velocity[i] = vp;
      p.position[i] = x;
      if (!detail::finiteMotion(vp, x)) {
        if (r.notFinite == kNoParticle) r.notFinite = i;
        continue;
      }
      const Voigt d = detail::strainIncrement(at, dt);
      Voigt& stress = sig[count];
      const bool closedForm = materials[p.material[i]].closedFormStress(d, p.band[i] >= 0, p.strain[i], stress);
      if (!closedForm) {
        p.strainIncrement[i] = d;
        deferred.push_back(static_cast<std::uint32_t>(i));
      }
      StencilAt next;
      if (!locateStencil<F>(geometry, invCell, halfWidth, x, next)) {
        r.leftGrid = true;  // reported by the next step's scatterState, as the separate transfers do
        if (closedForm) p.stress[i] = stress;
        continue;
      }
      p.stencilAt[i] = next;
      span.add(next.base);
      if (next.base < lo || next.base >= hi) {  // far: scatters after the colours (scatterDeferred)
        far.push_back(static_cast<std::uint32_t>(i));
        if (closedForm) p.stress[i] = stress;
        continue;
      }
      if (closedForm) scatters[count++] = static_cast<std::uint32_t>(i);
    }
    for (std::size_t k = 0; k < count; ++k) {
      const std::uint32_t i = scatters[k];
      Stencil s;
      expandStencil<F>(p.stencilAt[i], invCell, halfWidth, s);
      const SharedMassVolume mv = shared ? shared[p.material[i]] : SharedMassVolume{p.mass[i], p.volume[i]};
      detail::scatterParticle<F, true, true>(s, nx, mv.mass, p.velocity[i], mv.volume, sig[k], gravity, withGravity,
                                             out);
    }
  }
  measured = span.rows(nx);
  return r;
}

// Scatters the listed particles of chunk c (or of no chunk: c = npos) that are within its plan,
// from their stored stencils; Locate: locate them first (a rebuild). Returns the first particle
// whose stencil left the grid.
template <ShapeFunction F, bool Locate>
std::size_t scatterList(const TransferSetup& t, Particles& p, std::size_t c, const std::uint32_t* begin,
                        const std::uint32_t* end, ScatterTarget out) {
  const int nx = t.grid.nodesX();
  const auto [lo, hi] = c == kNoParticle ? std::pair<std::int64_t, std::int64_t>{INT64_MIN, INT64_MAX} : t.order.plannedBases(c);
  std::size_t bad = kNoParticle;
  for (const std::uint32_t* l = begin; l != end; ++l) {
    const std::uint32_t i = *l;
    if constexpr (Locate)
      if (!locateStencil<F>(t.grid, t.invCell, t.halfWidth, p.position[i], p.stencilAt[i])) {
        bad = std::min<std::size_t>(bad, i);
        continue;
      }
    if (p.stencilAt[i].base < lo || p.stencilAt[i].base >= hi) continue;  // far
    Stencil s;
    expandStencil<F>(p.stencilAt[i], t.invCell, t.halfWidth, s);
    detail::scatterParticle<F, true, true>(s, nx, p, i, t.gravity, t.withGravity, out);
  }
  return bad;
}

// A rebuild's chunk: its particles that are `deferred` (or not), located at their positions;
// those within the chunk's plan scatter, the far ones go to `far`.
template <ShapeFunction F>
std::size_t rebuildChunk(const TransferSetup& t, Particles& p, std::size_t c, const std::vector<std::uint8_t>& isDeferred,
                         bool deferred, ScatterTarget out, std::vector<std::uint32_t>& far) {
  const int nx = t.grid.nodesX();
  const auto [first, last] = t.order.range(c, p.size());
  const auto [lo, hi] = t.order.plannedBases(c);
  std::size_t bad = kNoParticle;
  for (std::size_t i = first; i < last; ++i) {
    if ((isDeferred[i] != 0) != deferred) continue;
    StencilAt& at = p.stencilAt[i];
    if (!locateStencil<F>(t.grid, t.invCell, t.halfWidth, p.position[i], at)) {
      bad = std::min(bad, i);
      continue;
    }
    if (at.base < lo || at.base >= hi) {
      far.push_back(static_cast<std::uint32_t>(i));
      continue;
    }
    Stencil s;
    expandStencil<F>(at, t.invCell, t.halfWidth, s);
    detail::scatterParticle<F, true, true>(s, nx, p, i, t.gravity, t.withGravity, out);
  }
  return bad;
}

}  // namespace

void scatterState(const StepSetup& setup, long step, Particles& particles, GridFields& grid, ScatterOrder& order,
                  const FusedPass& fused) {
  const Scene& scene = setup.scene;
  const int threads = setup.threads;
  std::vector<std::uint8_t> isDeferred(particles.size(), 0);
  for (const std::uint32_t i : fused.deferred) isDeferred[i] = 1;
  detail::zeroScatterFields(threads, grid, true, true);
  const TransferSetup tr = setupOf(setup, order);
  const ScatterTarget target = detail::targetOf(grid);
  std::vector<std::vector<std::uint32_t>> far(static_cast<std::size_t>(threads));
  std::vector<std::size_t> bad(static_cast<std::size_t>(threads), kNoParticle);
  order.far.clear();
  withShapeFunction(scene.solver.shapeFunction, [&]<ShapeFunction F>() {
    for (const bool deferred : {false, true})  // the pass's order: closed-form points, then the deferred ones
      forEachChunkByColour(order, threads, [&](std::size_t c, int th) {
        const auto k = static_cast<std::size_t>(th);
        bad[k] = std::min(bad[k], rebuildChunk<F>(tr, particles, c, isDeferred, deferred, target, far[k]));
      });
    detail::mergeSorted(far, order.far);  // then the far points, deferred or not, in index order
    scatterList<F, false>(tr, particles, kNoParticle, order.far.data(), order.far.data() + order.far.size(), target);
  });
  const std::size_t first = *std::min_element(bad.begin(), bad.end());
  if (first != kNoParticle) detail::throwLeftGrid(scene, step, particles, first);
}

bool gatherStressScatter(const StepSetup& setup, const Clock& clock, GridFields& grid, Particles& particles,
                         ScatterOrder& order, FusedPass& fused) {
  const Scene& scene = setup.scene;
  const int threads = setup.threads;
  const auto parts = static_cast<std::size_t>(threads);
  planScatter(order, scene.grid.nodesY());  // from where the stencils started in the last step
  detail::zeroScatterFields(threads, grid, true, true);
  const TransferSetup tr = setupOf(setup, order);
  const ScatterTarget target = detail::targetOf(grid);
  fused.deferredPerThread.resize(parts);
  fused.farPerThread.resize(parts);
  for (auto& d : fused.deferredPerThread) d.clear();
  // Per chunk: the thread that ran it and its deferred points' range in that thread's list.
  struct Segment {
    int thread = 0;
    std::uint32_t begin = 0, end = 0;
  };
  std::vector<Segment> segments(order.chunks());
  std::vector<ChunkOutcome> outcome(parts);
  const SharedMassVolume* shared = fused.shared.empty() ? nullptr : fused.shared.data();
  withShapeFunction(scene.solver.shapeFunction, [&]<ShapeFunction F>() {
    forEachChunkByColour(order, threads, [&](std::size_t c, int th) {
      const auto k = static_cast<std::size_t>(th);
      std::vector<std::uint32_t>& mine = fused.deferredPerThread[k];
      const auto begin = static_cast<std::uint32_t>(mine.size());
      const ChunkOutcome o = gatherStressScatter<F>(tr, grid, particles, c, clock.dt, scene.solver.explicitScheme.flip,
                                                    setup.materials.data(), shared, target, order.measured[c], mine,
                                                    fused.farPerThread[k]);
      segments[c] = {th, begin, static_cast<std::uint32_t>(mine.size())};
      outcome[k].notFinite = std::min(outcome[k].notFinite, o.notFinite);
      outcome[k].leftGrid = outcome[k].leftGrid || o.leftGrid;
    });
  });
  // The deferred points chunk after chunk: in index order.
  fused.deferred.clear();
  fused.chunkDeferred.resize(order.chunks());
  for (std::size_t c = 0; c < order.chunks(); ++c) {
    const Segment& s = segments[c];
    const std::vector<std::uint32_t>& list = fused.deferredPerThread[static_cast<std::size_t>(s.thread)];
    const auto start = static_cast<std::uint32_t>(fused.deferred.size());
    fused.deferred.insert(fused.deferred.end(), list.begin() + s.begin, list.begin() + s.end);
    fused.chunkDeferred[c] = {start, static_cast<std::uint32_t>(fused.deferred.size())};
  }
  order.far.clear();
  detail::mergeSorted(fused.farPerThread, order.far);
  std::size_t notFinite = kNoParticle;
  bool leftGrid = false;
  for (const ChunkOutcome& o : outcome) {
    notFinite = std::min(notFinite, o.notFinite);
    leftGrid = leftGrid || o.leftGrid;
  }
  if (notFinite != kNoParticle) detail::throwNotFinite(clock.step, particles, notFinite);
  return !leftGrid;
}

void scatterDeferred(const StepSetup& setup, Particles& particles, GridFields& grid, const ScatterOrder& order,
                     const FusedPass& fused) {
  const TransferSetup tr = setupOf(setup, order);
  const ScatterTarget target = detail::targetOf(grid);
  withShapeFunction(setup.scene.solver.shapeFunction, [&]<ShapeFunction F>() {
    forEachChunkByColour(
        order, setup.threads,
        [&](std::size_t c, int) {
          const auto [begin, end] = fused.chunkDeferred[c];
          scatterList<F, false>(tr, particles, c, fused.deferred.data() + begin, fused.deferred.data() + end, target);
        },
        GroupSchedule::Dynamic);  // the deferred points sit in the cracked rows
    scatterList<F, false>(tr, particles, kNoParticle, order.far.data(), order.far.data() + order.far.size(), target);
  });
}

}  // namespace ecm::mpm
