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
// docs/performance.md "Scaling with the cores" has the design and its measurements.
#include <omp.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <utility>
#include <vector>

#include "mpm/grid.hpp"

namespace ecm::mpm {

inline constexpr int kColours = 3;

// Node rows [lo, hi] (lo > hi: none).
struct RowSpan {
  int lo = 1, hi = 0;
  bool empty() const { return lo > hi; }
};

struct ScatterOrder {
  std::size_t chunk = 1;  // particles per chunk
  int nodesX = 1;         // nodes per grid row: a stencil base's row is base / nodesX
  int support = 2;        // nodes per direction of a stencil
  std::vector<RowSpan> measured;  // per chunk: the rows its stencils started on at the last scatter that located them
  std::vector<RowSpan> planned;   // per chunk: the rows a stencil may start on to scatter with the chunk's colour
  // Per colour: its groups, each a list of chunks in index order; groups of a colour share no node.
  std::array<std::vector<std::vector<std::int32_t>>, kColours> groups;
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
// The groups of each colour from the planned rows (the same for any thread count).
void groupChunks(ScatterOrder& order);

// Tracks the lowest and highest stencil base of a chunk while it scatters.
struct BaseSpan {
  std::int32_t lo = INT32_MAX, hi = INT32_MIN;
  void add(std::int32_t base) {
    lo = base < lo ? base : lo;
    hi = base > hi ? base : hi;
  }
  RowSpan rows(int nodesX) const { return lo > hi ? RowSpan{} : RowSpan{lo / nodesX, hi / nodesX}; }
};

// How the groups of a colour are shared among the threads. Static: each thread takes the same
// contiguous share of every colour's groups, so it scatters into the same band of grid rows at
// every step, and the grid update (which splits the nodes statically too, mpm/ordered_sum.hpp)
// finds those rows in its own cache: with a dynamic share the other core held half of them and
// the grid phase of a 2-thread run took twice as long as on one thread (docs/performance.md).
// Dynamic: for passes whose cost sits in a few groups (the deferred, cracked points).
enum class GroupSchedule { Static, Dynamic };

// Runs body(chunk, thread) for every chunk, colour after colour; the groups of a colour run in
// parallel, the chunks of a group in index order, and a colour starts when the previous one is
// done. The schedule changes which thread runs a group, never the order of any node's sums.
template <class Body>
void forEachChunkByColour(const ScatterOrder& o, int threads, Body&& body,
                          GroupSchedule schedule = GroupSchedule::Static) {
  const bool dynamic = schedule == GroupSchedule::Dynamic;
#pragma omp parallel num_threads(threads)
  {
    const int t = omp_get_thread_num();
    for (const auto& groups : o.groups) {
      const auto n = static_cast<long>(groups.size());
      const auto run = [&](long g) {
        for (const std::int32_t c : groups[static_cast<std::size_t>(g)]) body(static_cast<std::size_t>(c), t);
      };
      if (dynamic) {
#pragma omp for schedule(dynamic, 1)
        for (long g = 0; g < n; ++g) run(g);
      } else {
#pragma omp for schedule(static)
        for (long g = 0; g < n; ++g) run(g);
      }
    }
  }
}

}  // namespace ecm::mpm
