// Where a crack may start (docs/model.md, "Crack paths", roots).
#include "mpm/setup/crack_roots.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace ecm::mpm {

namespace {

// The distance from x to the box (0 inside it).
double distanceTo(const Box& b, const Vec2& x) {
  const Vec2 out = (b.min - x).cwiseMax(x - b.max).cwiseMax(Vec2::Zero());
  return out.norm();
}

bool holdsOrMoves(const NodeCondition& c) {
  if (c.field) return true;
  return std::any_of(c.component.begin(), c.component.end(), [](const ComponentCondition& k) { return k.kind != Prescribed::Free; });
}

}  // namespace

std::vector<CellIndex> rootCells(const Scene& scene, const Particles& particles, double exclusion) {
  const Grid& g = scene.grid;
  // Which materials each cell holds, one bit each (a 65th material shares the last bit).
  std::vector<std::uint64_t> holds(static_cast<std::size_t>(g.cellsX) * static_cast<std::size_t>(g.cellsY), 0);
  for (std::size_t p = 0; p < particles.size(); ++p) {
    const Vec2 r = (particles.origin[p] - g.origin).cwiseQuotient(g.cellSize);
    const auto i = static_cast<long>(std::floor(r[0])), j = static_cast<long>(std::floor(r[1]));
    if (i < 0 || j < 0 || i >= g.cellsX || j >= g.cellsY) continue;
    holds[static_cast<std::size_t>(j * g.cellsX + i)] |= std::uint64_t{1} << std::min<int>(particles.material[p], 63);
  }
  const auto heldBy = [&](long i, long j) -> std::uint64_t {
    if (i < 0 || j < 0 || i >= g.cellsX || j >= g.cellsY) return 0;
    return holds[static_cast<std::size_t>(j * g.cellsX + i)];
  };
  std::vector<const Box*> held;
  for (const NodeCondition& c : scene.conditions)
    if (holdsOrMoves(c)) held.push_back(&c.box);
  for (const Platen& p : scene.platens)
    for (const Box& b : p.boxes) held.push_back(&b);
  std::vector<CellIndex> cells;
  for (long j = 0; j < g.cellsY; ++j)
    for (long i = 0; i < g.cellsX; ++i) {
      const std::uint64_t mine = heldBy(i, j);
      if (mine == 0) continue;
      bool surface = false;
      for (long dj = -1; dj <= 1 && !surface; ++dj)
        for (long di = -1; di <= 1 && !surface; ++di) surface = (heldBy(i + di, j + dj) & mine) != mine;
      if (!surface) continue;
      const Vec2 centre = g.origin + Vec2((static_cast<double>(i) + 0.5) * g.cellSize[0], (static_cast<double>(j) + 0.5) * g.cellSize[1]);
      if (std::any_of(held.begin(), held.end(), [&](const Box* b) { return distanceTo(*b, centre) < exclusion; })) continue;
      cells.push_back({i, j});
    }
  return cells;
}

}  // namespace ecm::mpm
