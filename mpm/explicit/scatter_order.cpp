#include "mpm/explicit/scatter_order.hpp"

#include <algorithm>

namespace ecm::mpm {

void layOutChunks(const Grid& grid, int particlesPerCell, int support, std::size_t particles, ScatterOrder& order) {
  // About two rows of cells of particles: with three colours, two chunks of a colour are then
  // about four rows apart, more than a stencil's reach, and a colour has many groups.
  const auto perRow = static_cast<std::size_t>(particlesPerCell) * static_cast<std::size_t>(particlesPerCell) *
                      static_cast<std::size_t>(grid.cellsX);
  order.chunk = std::max<std::size_t>(256, 2 * perRow);
  order.nodesX = grid.nodesX();
  order.support = support;
  order.measured.assign((particles + order.chunk - 1) / order.chunk, RowSpan{});
  order.planned.assign(order.measured.size(), RowSpan{});
  for (auto& g : order.groups) g.clear();
  order.waits = GroupWaits{};
  order.waits.waitsBegin.assign(1, 0);
  order.far.clear();
}

void planScatter(ScatterOrder& o, int nodeRows) {
  const std::size_t n = o.chunks();
  o.planned.resize(n);
  for (std::size_t c = 0; c < n; ++c) {
    const RowSpan m = o.measured[c];
    o.planned[c] = m.empty() ? RowSpan{} : RowSpan{std::max(0, m.lo - 1), std::min(nodeRows - 1, m.hi + 1)};
  }
  groupChunks(o);
}

void groupChunks(ScatterOrder& o) {
  const std::size_t n = o.chunks();
  struct Member {
    int lo, hi;  // node rows the chunk's stencils may reach
    std::int32_t chunk;
  };
  std::vector<Member> members;
  for (int colour = 0; colour < kColours; ++colour) {
    auto& groups = o.groups[static_cast<std::size_t>(colour)];
    groups.clear();
    members.clear();
    std::vector<std::int32_t> unplanned;  // nothing of them scatters with the colour: their particles go far
    for (std::size_t c = static_cast<std::size_t>(colour); c < n; c += kColours) {
      const RowSpan p = o.planned[c];
      if (p.empty())
        unplanned.push_back(static_cast<std::int32_t>(c));
      else
        members.push_back({p.lo, p.hi + o.support - 1, static_cast<std::int32_t>(c)});
    }
    // Chunks whose reaches overlap, directly or through others, form a group.
    std::sort(members.begin(), members.end(),
              [](const Member& a, const Member& b) { return a.lo != b.lo ? a.lo < b.lo : a.chunk < b.chunk; });
    int reach = -1;  // the highest node row of the group being built
    for (const Member& m : members) {
      if (groups.empty() || m.lo > reach) {
        groups.push_back({m.chunk});
        reach = m.hi;
      } else {
        groups.back().push_back(m.chunk);
        reach = std::max(reach, m.hi);
      }
    }
    for (auto& g : groups) std::sort(g.begin(), g.end());  // a group's chunks scatter in index order
    for (const std::int32_t c : unplanned) groups.push_back({c});
  }
  linkGroups(o);
}

void linkGroups(ScatterOrder& o) {
  GroupWaits& w = o.waits;
  w.bandPosition.clear();
  w.waitsBegin.assign(1, 0);
  w.waits.clear();
  const double chunks = static_cast<double>(std::max<std::size_t>(1, o.chunks()));
  // Per colour, its planned groups' node rows [lo, hi] and list entries, in the order of lo;
  // the groups of one colour reach no common row, so their hi are in that order too.
  struct Reach {
    int lo, hi;
    std::int32_t entry;
  };
  std::array<std::vector<Reach>, kColours> reaches;
  std::int32_t entry = 0;
  for (int colour = 0; colour < kColours; ++colour) {
    w.firstOfColour[static_cast<std::size_t>(colour)] = entry;
    for (const auto& group : o.groups[static_cast<std::size_t>(colour)]) {
      double middle = 0.0;
      int lo = INT32_MAX, hi = INT32_MIN;
      for (const std::int32_t c : group) {
        middle += (c + 0.5) / chunks;
        const RowSpan p = o.planned[static_cast<std::size_t>(c)];
        if (p.empty()) continue;
        lo = std::min(lo, p.lo);
        hi = std::max(hi, p.hi + o.support - 1);
      }
      w.bandPosition.push_back(middle / static_cast<double>(group.size()));
      if (lo <= hi) {  // the earlier colours' groups it shares a row with
        for (int earlier = 0; earlier < colour; ++earlier) {
          const auto& r = reaches[static_cast<std::size_t>(earlier)];
          auto it = std::lower_bound(r.begin(), r.end(), lo, [](const Reach& a, int row) { return a.hi < row; });
          for (; it != r.end() && it->lo <= hi; ++it) w.waits.push_back(it->entry);
        }
        reaches[static_cast<std::size_t>(colour)].push_back({lo, hi, entry});
      }
      w.waitsBegin.push_back(static_cast<std::int32_t>(w.waits.size()));
      ++entry;
    }
  }
  w.firstOfColour[kColours] = entry;
}

}  // namespace ecm::mpm
