#pragma once
// The order in which particles scatter to the grid, the same on any number of threads.
//
// The particles are cut into chunks of consecutive indices (ScatterOrder::chunk each, about two
// rows of cells of particles: the seeding goes row by row), and the chunks are coloured by their
// index modulo kColours. Each chunk knows the node rows its particles' stencils start on; within
// a colour, chunks whose rows (with the stencils' reach) overlap form a group, and groups share
// no node. The groups of a colour scatter at once, straight into the grid, with no per-thread
// copy of it and no locks; the chunks of a group scatter one after the other. Colour after
// colour, every node therefore sums its particles in one fixed order (colour, chunk, particle
// index), whatever the thread count and the schedule. The traversal stays in index order inside
// a chunk, so the particle arrays stream through the cache as in a plain loop.
//
// The rows a chunk may start on in a scatter are planned from the rows it started on in the
// last one, widened by a row each way (a particle moves less than a cell per step). A particle
// outside its chunk's plan ("far": it moved a cell or more in a step, or was edited between
// steps) scatters after the colours, alone, in index order.
//
// Threads need no barrier between the colours: a group waits only for the groups of earlier
// colours that reach one of its node rows (GroupWaits), and each thread takes a band of the
// particles (the groups whose chunks fall in its share of the chunk order) through all colours.
// A node's sums keep the order (colour, chunk, index); which thread runs a group never changes it.
// docs/performance.md "Scaling with the cores" has the design and its measurements.
#include <omp.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cstdint>
#include <utility>
#include <vector>

#include "mpm/core/grid.hpp"

namespace ecm::mpm {

inline constexpr int kColours = 3;

// Node rows [lo, hi] (lo > hi: none).
struct RowSpan {
  int lo = 1, hi = 0;
  bool empty() const { return lo > hi; }
};

// The groups of all colours in one list (colour by colour, each colour's groups in the order of
// ScatterOrder::groups), with what lets the threads run them without a barrier between colours.
struct GroupWaits {
  std::array<std::int32_t, kColours + 1> firstOfColour{};  // colour k: list entries [first[k], first[k + 1])
  std::vector<double> bandPosition;  // per entry: the middle of its chunks in the chunk order, in [0, 1)
  std::vector<std::int32_t> waitsBegin;  // per entry + 1: its waits are waits[waitsBegin[g], waitsBegin[g + 1])
  std::vector<std::int32_t> waits;       // entries of earlier colours that reach one of its node rows
  std::size_t size() const { return bandPosition.size(); }
};

struct ScatterOrder {
  std::size_t chunk = 1;  // particles per chunk
  int nodesX = 1;         // nodes per grid row: a stencil base's row is base / nodesX
  int support = 2;        // nodes per direction of a stencil
  std::vector<RowSpan> measured;  // per chunk: the rows its stencils started on at the last scatter that located them
  std::vector<RowSpan> planned;   // per chunk: the rows a stencil may start on to scatter with the chunk's colour
  // Per colour: its groups, each a list of chunks in index order; groups of a colour share no node.
  std::array<std::vector<std::vector<std::int32_t>>, kColours> groups;
  GroupWaits waits;                // the groups as one list, with their waits (groupChunks)
  std::vector<std::uint32_t> far;  // particles that scatter after the colours (index order)

  std::size_t chunks() const { return measured.size(); }
  std::pair<std::size_t, std::size_t> range(std::size_t c, std::size_t particles) const {
    return {c * chunk, std::min(particles, (c + 1) * chunk)};
  }
  // Node indices [first, last) a stencil base of chunk c may have to scatter with its colour.
  std::pair<std::int64_t, std::int64_t> plannedBases(std::size_t c) const {
    const RowSpan r = planned[c];
    return {static_cast<std::int64_t>(r.lo) * nodesX, static_cast<std::int64_t>(r.hi + 1) * nodesX};
  }
};

// The chunks of `particles` particles on a grid (k x k particles per cell), rows not yet measured.
void layOutChunks(const Grid& grid, int particlesPerCell, int support, std::size_t particles, ScatterOrder& order);
// The plan of the next scatter: each chunk's measured rows widened by a row each way
// (planned), then its groups.
void planScatter(ScatterOrder& order, int nodeRows);
// The groups of each colour from the planned rows (the same for any thread count), then linkGroups.
void groupChunks(ScatterOrder& order);
// ScatterOrder::waits from the groups: each group's band position and the groups of earlier
// colours it waits for.
void linkGroups(ScatterOrder& order);

// Tracks the lowest and highest stencil base of a chunk while it scatters.
struct BaseSpan {
  std::int32_t lo = INT32_MAX, hi = INT32_MIN;
  void add(std::int32_t base) {
    lo = base < lo ? base : lo;
    hi = base > hi ? base : hi;
  }
  RowSpan rows(int nodesX) const { return lo > hi ? RowSpan{} : RowSpan{lo / nodesX, hi / nodesX}; }
};

// How the groups are shared among the threads. Static: each thread takes a band of the chunk
// order through all colours (GroupWaits::bandPosition), so it scatters into the same band of grid
// rows at every step, and the grid update (which splits the nodes statically too,
// mpm/core/ordered_sum.hpp) finds those rows in its own cache; there is no barrier between colours,
// and a thread with less work in one colour goes on with the next. Dynamic: colour after colour,
// the groups of a colour handed out one at a time, for passes whose cost sits in a few groups
// (the deferred, cracked points).
enum class GroupSchedule { Static, Dynamic };

namespace detail {

// Waits until another thread has marked the entry done (acquire: its scatter is visible): a
// short spin, then asleep until markDone wakes it (more threads than cores must not spin).
inline void waitUntilDone(std::uint32_t& flag) {
  const std::atomic_ref<std::uint32_t> done(flag);
  for (int spins = 0; spins < 2048; ++spins)
    if (done.load(std::memory_order_acquire) != 0) return;
  while (done.load(std::memory_order_acquire) == 0) done.wait(0, std::memory_order_acquire);
}

inline void markDone(std::uint32_t& flag) {
  const std::atomic_ref<std::uint32_t> done(flag);
  done.store(1, std::memory_order_release);
  done.notify_all();
}

// The thread (of `threads`) whose band holds a group at `position` of the chunk order.
inline int bandOwner(double position, int threads) {
  return std::min(threads - 1, static_cast<int>(position * threads));
}

}  // namespace detail

// Runs body(chunk, thread) for every chunk, the chunks of a group in index order, and a group
// only once every group of an earlier colour that reaches one of its node rows is done. The
// schedule changes which thread runs a group, never the order of any node's sums.
template <class Body>
void forEachChunkByColour(const ScatterOrder& o, int threads, Body&& body,
                          GroupSchedule schedule = GroupSchedule::Static) {
  const auto runGroup = [&](const std::vector<std::int32_t>& group, int t) {
    for (const std::int32_t c : group) body(static_cast<std::size_t>(c), t);
  };
  if (schedule == GroupSchedule::Dynamic) {
#pragma omp parallel num_threads(threads)
    {
      const int t = omp_get_thread_num();
      for (const auto& groups : o.groups) {
        const auto n = static_cast<long>(groups.size());
#pragma omp for schedule(dynamic, 1)
        for (long g = 0; g < n; ++g) runGroup(groups[static_cast<std::size_t>(g)], t);
      }
    }
    return;
  }
  const GroupWaits& w = o.waits;
  std::vector<std::uint32_t> done(w.size(), 0);
#pragma omp parallel num_threads(threads)
  {
    const int t = omp_get_thread_num(), team = omp_get_num_threads();
    for (int colour = 0; colour < kColours; ++colour) {
      const std::int32_t first = w.firstOfColour[static_cast<std::size_t>(colour)];
      const std::int32_t count = w.firstOfColour[static_cast<std::size_t>(colour) + 1] - first;
      const auto& groups = o.groups[static_cast<std::size_t>(colour)];
      // Even threads go up their band, odd ones down: two neighbours reach their common edge
      // at the same point of each colour (both first or both last), so a group at the edge
      // waits only when the neighbour is a whole colour behind.
      for (std::int32_t k = 0; k < count; ++k) {
        const std::int32_t g = t % 2 == 0 ? k : count - 1 - k;
        const auto e = static_cast<std::size_t>(first + g);
        if (detail::bandOwner(w.bandPosition[e], team) != t) continue;
        for (std::int32_t i = w.waitsBegin[e]; i < w.waitsBegin[e + 1]; ++i)
          detail::waitUntilDone(done[static_cast<std::size_t>(w.waits[static_cast<std::size_t>(i)])]);
        runGroup(groups[static_cast<std::size_t>(g)], t);
        detail::markDone(done[e]);
      }
    }
  }
}

}  // namespace ecm::mpm
