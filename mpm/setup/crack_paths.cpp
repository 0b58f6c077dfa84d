// Crack paths: the geometry of the tracking rule (docs/model.md, "Crack paths").
#include "mpm/setup/crack_paths.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ecm::mpm {

CrackPathGeometry CrackPathGeometry::forGrid(const Vec2& origin, const Vec2& cellSize) {
  CrackPathGeometry g;
  g.origin = origin;
  g.cellSize = cellSize;
  const double cell = std::sqrt(cellSize[0] * cellSize[1]);
  g.lookAhead = 2.0 * cell;  // docs/model.md, "Crack paths": past the points near onset ahead of a tip
  g.averaging = std::max(2.0 * cell, 5.0);  // at least 5 mm (docs/model.md, "Crack paths")
  g.exclusion = std::max(4.0 * cell, 10.0);  // at least 10 mm (docs/model.md, "Crack paths")
  g.shortestChord = 0.02 * cell;  // docs/model.md, "Crack paths"
  g.turnEvery = 0.5 * cell;
  g.interiorOverstress = 1.5;  // docs/model.md, "Crack paths"
  g.smallestKink = 5.0 * std::acos(-1.0) / 180.0;  // 5 degrees (docs/model.md, "Crack paths")
  g.smallestRadius = 3.0 * g.averaging;             // docs/model.md, "Crack paths"
  return g;
}

CrackPaths::CrackPaths(CrackPathRule rule, const CrackPathGeometry& geometry, const std::vector<CellIndex>& roots)
    : rule_(rule), geometry_(geometry), rootCells_(std::in_place) {
  for (const CellIndex& c : roots) rootCells_->insert((static_cast<CellKey>(c.j) << 32) + c.i);
}

CrackPaths crackPathsFor(const Scene& scene, const Particles& particles) {
  const CrackPathGeometry geometry = CrackPathGeometry::forGrid(scene.grid.origin, scene.grid.cellSize);
  if (scene.solver.crackPath != CrackPathRule::Tracked) return {scene.solver.crackPath, geometry};
  return {scene.solver.crackPath, geometry, rootCells(scene, particles, geometry.exclusion)};
}

namespace {

Vec2 perpendicular(const Vec2& d) { return {-d[1], d[0]}; }

// The length of segment a-b inside the box [lo, hi) (Liang-Barsky clipping). A segment that runs
// along the box's upper or right edge belongs to the next cell, so that a path on a grid line
// crosses the cells on one side of it only.
double clippedLength(const Vec2& a, const Vec2& b, const Vec2& lo, const Vec2& hi) {
  const Vec2 d = b - a;
  double t0 = 0.0, t1 = 1.0;
  for (int k = 0; k < 2; ++k) {
    if (d[k] == 0.0) {
      if (a[k] < lo[k] || a[k] >= hi[k]) return 0.0;
      continue;
    }
    double ta = (lo[k] - a[k]) / d[k], tb = (hi[k] - a[k]) / d[k];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  return t1 > t0 ? (t1 - t0) * d.norm() : 0.0;
}

}  // namespace

Vec2 kinkedDirection(const Vec2& direction, const Voigt& s) {
  const Vec2 n = perpendicular(direction);
  const Vec2 sn(s[0] * n[0] + s[2] * n[1], s[2] * n[0] + s[1] * n[1]);  // sigma n
  const double opening = n.dot(sn), shear = direction.dot(sn);
  if (!(opening > 0.0) || shear == 0.0) return direction;
  // theta = 2 atan((K_I - sqrt(K_I^2 + 8 K_II^2)) / (4 K_II)), counter-clockwise from the crack's
  // line, with K_I, K_II in the ratio of max(sigma_nn, 1) and sigma_nt (Erdogan and Sih 1963)
  const double driving = std::max(opening, 1.0);
  const double theta = 2.0 * std::atan((driving - std::sqrt(driving * driving + 8.0 * shear * shear)) / (4.0 * shear));
  const double c = std::cos(theta), si = std::sin(theta);
  return Vec2(c * direction[0] - si * direction[1], si * direction[0] + c * direction[1]).normalized();
}

CrackPaths::CellKey CrackPaths::cellOf(const Vec2& x) const {
  const auto ix = static_cast<CellKey>(std::floor((x[0] - geometry_.origin[0]) / geometry_.cellSize[0]));
  const auto iy = static_cast<CellKey>(std::floor((x[1] - geometry_.origin[1]) / geometry_.cellSize[1]));
  return (iy << 32) + ix;  // (a grid has far fewer than 2^31 cells a side)
}

void CrackPaths::index() {
  crossed_.clear();
  near_.clear();
  const Vec2& h = geometry_.cellSize;
  struct Pieces {
    double chord = 0.0, longest = 0.0;
    Vec2 along = Vec2::UnitY();
  };
  std::unordered_map<CellKey, Pieces> pieces;
  const auto reach = static_cast<long>(std::ceil(geometry_.exclusion / std::min(h[0], h[1])));
  const auto add = [&](const Vec2& a, const Vec2& b) {
    if (a == b) return;  // (a tip that has just become a vertex)
    const Vec2 lo = a.cwiseMin(b), hi = a.cwiseMax(b);
    const auto i0 = static_cast<long>(std::floor((lo[0] - geometry_.origin[0]) / h[0])),
               i1 = static_cast<long>(std::floor((hi[0] - geometry_.origin[0]) / h[0]));
    const auto j0 = static_cast<long>(std::floor((lo[1] - geometry_.origin[1]) / h[1])),
               j1 = static_cast<long>(std::floor((hi[1] - geometry_.origin[1]) / h[1]));
    for (long j = j0; j <= j1; ++j)
      for (long i = i0; i <= i1; ++i) {
        const Vec2 cellLo(geometry_.origin[0] + i * h[0], geometry_.origin[1] + j * h[1]);
        const double l = clippedLength(a, b, cellLo, cellLo + h);
        if (l <= 0.0) continue;
        Pieces& p = pieces[(static_cast<CellKey>(j) << 32) + i];
        p.chord += l;
        if (l > p.longest) p.longest = l, p.along = (b - a).normalized();
      }
    for (long j = j0 - reach; j <= j1 + reach; ++j)
      for (long i = i0 - reach; i <= i1 + reach; ++i) near_.insert((static_cast<CellKey>(j) << 32) + i);
  };
  for (const CrackArm& arm : arms_) {
    for (std::size_t k = 0; k + 1 < arm.points.size(); ++k) add(arm.points[k], arm.points[k + 1]);
    add(arm.points.back(), arm.points.back() + geometry_.lookAhead * arm.direction);
    if (arm.points.size() == 1) {  // (a root alone: its cell's neighbourhood is near)
      const Vec2& r = arm.points[0];
      add(r, r + 1e-9 * arm.direction);
    }
  }
  for (const auto& [key, p] : pieces)
    if (p.chord >= geometry_.shortestChord) crossed_[key] = PathCrossing{perpendicular(p.along), p.chord, h[0] * h[1] / p.chord};
}

std::optional<PathCrossing> CrackPaths::crossingAt(const Vec2& x) const {
  const auto it = crossed_.find(cellOf(x));
  if (it == crossed_.end()) return std::nullopt;
  return it->second;
}

std::size_t CrackPaths::grow(const std::vector<Vec2>& opened, std::vector<OnsetCandidate> candidates,
                             const AveragedStress& averaged) {
  if (!tracked()) return 0;
  const double cell = std::sqrt(geometry_.cellSize[0] * geometry_.cellSize[1]);
  // 1. Tips: the farthest opened point in each arm's look-ahead (a cell on either side of it). A
  // point opens anywhere in a cell the look-ahead crosses, so up to a cell's diagonal past the
  // look-ahead's end: such a point moves the tip to that end (were it ignored, the tip would stop
  // short of it, its look-ahead might cross no new cell, and the crack would stall).
  std::vector<double> advance(arms_.size(), 0.0);
  for (const Vec2& x : opened) {
    for (std::size_t a = 0; a < arms_.size(); ++a) {
      const CrackArm& arm = arms_[a];
      const Vec2 r = x - arm.points.back();
      const double along = r.dot(arm.direction);
      const double across = std::abs(r.dot(perpendicular(arm.direction)));
      if (along > 0.0 && along <= geometry_.lookAhead + std::sqrt(2.0) * cell && across <= cell) {
        advance[a] = std::max(advance[a], std::min(along, geometry_.lookAhead));
        break;  // a point moves one arm
      }
    }
  }
  for (std::size_t a = 0; a < arms_.size(); ++a) {
    if (advance[a] <= 0.0) continue;
    CrackArm& arm = arms_[a];
    // The last segment runs from the last vertex along `direction` to the tip: the tip moves on it.
    const Vec2 tip = arm.points.back() + advance[a] * arm.direction;
    if (arm.points.size() == 1) arm.points.push_back(tip);
    else arm.points.back() = tip;
    // Every half cell of advance the tip becomes a vertex and the direction is taken again there
    // (centred half a radius on: the tip's own flanks carry the crack's antisymmetric shear).
    if ((tip - arm.points[arm.points.size() - 2]).norm() < geometry_.turnEvery) continue;
    arm.points.push_back(tip);
    if (const std::optional<Voigt> ahead = averaged(tip + 0.5 * geometry_.averaging * arm.direction, geometry_.averaging)) {
      const Vec2 turned = kinkedDirection(arm.direction, *ahead);
      const double kink = std::atan2(arm.direction[0] * turned[1] - arm.direction[1] * turned[0], arm.direction.dot(turned));
      if (std::abs(kink) >= geometry_.smallestKink) {
        // at most turnEvery / smallestRadius: a path curves no tighter than that radius
        const double turn = std::copysign(std::min(std::abs(kink), geometry_.turnEvery / geometry_.smallestRadius), kink);
        const double c = std::cos(turn), si = std::sin(turn);
        arm.direction = Vec2(c * arm.direction[0] - si * arm.direction[1], si * arm.direction[0] + c * arm.direction[1]).normalized();
      }
    }
  }
  if (std::any_of(advance.begin(), advance.end(), [](double s) { return s > 0.0; })) index();
  // 2. Roots: candidates far from every path, the most overstressed first.
  std::stable_sort(candidates.begin(), candidates.end(), [](const OnsetCandidate& a, const OnsetCandidate& b) {
    return a.overstress > b.overstress || (a.overstress == b.overstress && a.particle < b.particle);
  });
  std::vector<std::uint8_t> used(candidates.size(), 0);
  for (std::size_t c = 0; c < candidates.size(); ++c) {
    if (used[c] || nearPath(candidates[c].position) || !mayRoot(candidates[c])) continue;
    // The region's centre and stress: the candidates within the exclusion radius, by overstress.
    Vec2 centre = Vec2::Zero();
    Voigt stress = Voigt::Zero();
    double weight = 0.0;
    for (std::size_t k = c; k < candidates.size(); ++k) {
      if (used[k] || !mayRoot(candidates[k]) ||
          (candidates[k].position - candidates[c].position).norm() > geometry_.exclusion)
        continue;
      used[k] = 1;
      centre += candidates[k].overstress * candidates[k].position;
      stress += candidates[k].overstress * candidates[k].stress;
      weight += candidates[k].overstress;
    }
    centre /= weight;
    const Vec2& h = geometry_.cellSize;  // the centre of its cell
    for (int k = 0; k < 2; ++k)
      centre[k] = geometry_.origin[k] + (std::floor((centre[k] - geometry_.origin[k]) / h[k]) + 0.5) * h[k];
    const Vec2 d = perpendicular(principalStresses(stress).firstDirection);
    arms_.push_back({{centre}, d});
    arms_.push_back({{centre}, -d});
    index();
  }
  std::size_t onPath = 0;
  for (const OnsetCandidate& c : candidates) onPath += crossingAt(c.position) ? 1 : 0;
  return onPath;
}

}  // namespace ecm::mpm
