// Crack paths: the geometry of the tracking rule (docs/model.md, "Crack paths").
#include "mpm/setup/crack_paths.hpp"

#include "mpm/setup/band_kinematics.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace ecm::mpm {

CrackPathGeometry CrackPathGeometry::forGrid(const Vec2& origin, const Vec2& cellSize) {
  CrackPathGeometry g;
  g.origin = origin;
  g.cellSize = cellSize;
  const double cell = std::sqrt(cellSize[0] * cellSize[1]);
  g.lookAhead = 2.0 * cell;  // docs/model.md, "Crack paths": past the points near onset ahead of a tip
  g.averaging = std::max(2.0 * cell, 20.0);  // at least 20 mm (docs/model.md, "Crack paths")
  g.exclusion = std::max(4.0 * cell, 10.0);  // at least 10 mm (docs/model.md, "Crack paths")
  g.turnEvery = 0.5 * cell;
  g.interiorOverstress = 1.5;  // docs/model.md, "Crack paths"
  g.smallestKink = 5.0 * std::acos(-1.0) / 180.0;  // 5 degrees (docs/model.md, "Crack paths")
  g.smallestRadius = std::max(10.0, 3.0 * cell);    // docs/model.md, "Crack paths"
  return g;
}

CrackPaths::CrackPaths(CrackPathRule rule, const CrackPathGeometry& geometry, const std::vector<CellIndex>& roots)
    : rule_(rule), geometry_(geometry), rootCells_(std::in_place) {
  for (const CellIndex& c : roots) rootCells_->insert((static_cast<CellKey>(c.j) << 32) + c.i);
}

CrackPaths crackPathsFor(const Scene& scene, const Particles& particles) {
  CrackPathGeometry geometry = CrackPathGeometry::forGrid(scene.grid.origin, scene.grid.cellSize);
  geometry.pointsPerCell = scene.particlesPerCell;
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

// Whether segment a-b meets the closed box [lo, hi].
bool touches(const Vec2& a, const Vec2& b, const Vec2& lo, const Vec2& hi) {
  const Vec2 d = b - a;
  double t0 = 0.0, t1 = 1.0;
  for (int k = 0; k < 2; ++k) {
    if (d[k] == 0.0) {
      if (a[k] < lo[k] || a[k] > hi[k]) return false;
      continue;
    }
    double ta = (lo[k] - a[k]) / d[k], tb = (hi[k] - a[k]) / d[k];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  return t1 >= t0;
}

// The path's length shared among the band's cells (keyed as CrackPaths' cells: j << 32 plus i):
// `chords`, the path's length in each cell it crosses; `levels`, the mean length of phi's level
// lines in each band cell (band_kinematics.hpp). Each cell's effective sizes are then scaled to
// dissipate G_F times the length it was given, and the band dissipates G_F times the path's
// length however the path lies on the grid. Each band cell keeps its own piece of path up to its
// level lines' length; a piece longer than that (across a cell's diagonal), or in a cell not in
// the band, goes to the band cells around it (itself and its eight neighbours) in proportion to
// what they lack. (Kept in each cell alone, a cell the path only clips or touches would be given
// almost none and open with an H of many cells; the level lines alone are up to 20 % longer than
// a path across the grid's diagonal. A path along a grid axis gives every cell its own.)
std::unordered_map<std::int64_t, double> sharePathLength(const std::unordered_map<std::int64_t, double>& chords,
                                                         const std::unordered_map<std::int64_t, double>& levels) {
  const auto around = [](std::int64_t key, auto&& visit) {
    for (std::int64_t dj = -1; dj <= 1; ++dj)
      for (std::int64_t di = -1; di <= 1; ++di) visit(key + (dj << 32) + di);
  };
  std::unordered_map<std::int64_t, double> kept, lacks;
  for (const auto& [key, level] : levels) {
    const auto c = chords.find(key);
    kept[key] = std::min(c == chords.end() ? 0.0 : c->second, level);
    lacks[key] = level - kept[key];
  }
  std::unordered_map<std::int64_t, double> given = kept;
  for (const auto& [key, chord] : chords) {
    const auto k = kept.find(key);
    const double rest = chord - (k == kept.end() ? 0.0 : k->second);
    if (!(rest > 0.0)) continue;
    double lacking = 0.0, sum = 0.0;
    around(key, [&](std::int64_t n) {
      if (const auto it = levels.find(n); it != levels.end()) lacking += lacks[n], sum += it->second;
    });
    around(key, [&](std::int64_t n) {
      if (const auto it = levels.find(n); it != levels.end())
        given[n] += rest * (lacking > 0.0 ? lacks[n] / lacking : it->second / sum);
    });
  }
  return given;
}

}  // namespace

Vec2 kinkedDirection(const Vec2& direction, const Voigt& s) {
  const Vec2 n = perpendicular(direction);
  const Vec2 sn(s[0] * n[0] + s[2] * n[1], s[2] * n[0] + s[1] * n[1]);  // sigma n
  const double opening = n.dot(sn), shear = direction.dot(sn);
  if (!(opening > 0.0) || shear == 0.0) return direction;
  // A weak field ahead (a ligament's compression zone near its far edge) does not steer the tip:
  // it runs straight (docs/model.md, "Crack paths").
  if (opening < kLeastSteeringOpening && std::abs(shear) < 1.0) return direction;
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
  const double cell = std::sqrt(h[0] * h[1]);
  // Each arm as the polyline its band follows: root to tip, and on to the look-ahead's end.
  std::vector<std::vector<Vec2>> lines;
  lines.reserve(arms_.size());
  for (const CrackArm& arm : arms_) {
    lines.push_back(arm.points);
    lines.back().push_back(arm.points.back() + geometry_.lookAhead * arm.direction);
  }
  // The cells each segment crosses (its length in them) or touches (along an edge, at a node),
  // each cell given to the arm of its longest piece.
  struct Pieces {
    double chord = 0.0, longest = 0.0;
    std::size_t arm = 0;
    bool owned = false;
    long i = 0, j = 0;
  };
  std::unordered_map<CellKey, Pieces> pieces;
  const auto reach = static_cast<long>(std::ceil(geometry_.exclusion / std::min(h[0], h[1])));
  const double touch = 1e-9 * cell;
  // (a, b: a segment of arm `arm`; from, to: the part of it whose touching a cell counts, short of
  // the polyline's ends: the cell beyond a path that ends on a grid line is not the band's)
  const auto add = [&](const Vec2& a, const Vec2& b, std::size_t arm, const Vec2& from, const Vec2& to) {
    if (a == b) return;  // (a tip that has just become a vertex)
    const Vec2 lo = a.cwiseMin(b), hi = a.cwiseMax(b);
    const auto i0 = static_cast<long>(std::floor((lo[0] - geometry_.origin[0]) / h[0])),
               i1 = static_cast<long>(std::floor((hi[0] - geometry_.origin[0]) / h[0]));
    const auto j0 = static_cast<long>(std::floor((lo[1] - geometry_.origin[1]) / h[1])),
               j1 = static_cast<long>(std::floor((hi[1] - geometry_.origin[1]) / h[1]));
    for (long j = j0 - 1; j <= j1 + 1; ++j)
      for (long i = i0 - 1; i <= i1 + 1; ++i) {
        const Vec2 cellLo(geometry_.origin[0] + i * h[0], geometry_.origin[1] + j * h[1]);
        const double l = clippedLength(a, b, cellLo, cellLo + h);
        if (l <= 0.0 && !touches(from, to, cellLo - Vec2::Constant(touch), cellLo + h + Vec2::Constant(touch))) continue;
        Pieces& p = pieces[(static_cast<CellKey>(j) << 32) + i];
        p.i = i, p.j = j;
        p.chord += l;
        if (l > p.longest || !p.owned) {
          if (l > p.longest) p.longest = l;
          p.arm = arm;
          p.owned = true;
        }
      }
    for (long j = j0 - reach; j <= j1 + reach; ++j)
      for (long i = i0 - reach; i <= i1 + reach; ++i) near_.insert((static_cast<CellKey>(j) << 32) + i);
  };
  for (std::size_t a = 0; a < arms_.size(); ++a) {
    const std::vector<Vec2>& line = lines[a];
    for (std::size_t k = 0; k + 1 < line.size(); ++k) {
      const Vec2 step = line[k + 1] - line[k];
      const Vec2 inward = step.norm() > 0.0 ? Vec2(1e-6 * cell * step.normalized()) : Vec2::Zero();
      add(line[k], line[k + 1], a, k == 0 ? Vec2(line[k] + inward) : line[k],
          k + 2 == line.size() ? Vec2(line[k + 1] - inward) : line[k + 1]);
    }
  }
  // The band: the cells whose nodes lie on both sides of their arm (band_kinematics.hpp), each
  // with the mean length of phi's level lines in it.
  std::array<double, 16> levelLength{};
  for (unsigned s = 0; s < 16; ++s) levelLength[s] = sideGradientIntegral(static_cast<NodeSides>(s), h, geometry_.pointsPerCell, kLeastGradient);
  std::unordered_map<CellKey, double> bandLength;
  for (const auto& [key, p] : pieces) {
    const Vec2 cellLo(geometry_.origin[0] + p.i * h[0], geometry_.origin[1] + p.j * h[1]);
    const NodeSides sides = nodeSides(lines[p.arm], cellLo, h);
    if (!straddles(sides)) continue;
    crossed_[key] = CellBand{sides, p.chord, 1.0};
    bandLength[key] = levelLength[sides];
  }
  std::unordered_map<CellKey, double> chords;
  for (const auto& [key, p] : pieces) chords[key] = p.chord;
  const std::unordered_map<CellKey, double> given = sharePathLength(chords, bandLength);
  for (auto it = crossed_.begin(); it != crossed_.end();) {
    const auto g = given.find(it->first);
    const double length = g == given.end() ? 0.0 : g->second;
    if (length <= 0.0) {
      it = crossed_.erase(it);
      continue;
    }
    it->second.scale = bandLength[it->first] / length;
    ++it;
  }
}

std::optional<PathCrossing> CrackPaths::crossingAt(const Vec2& x) const {
  const CellKey key = cellOf(x);
  const auto it = crossed_.find(key);
  if (it == crossed_.end()) return std::nullopt;
  const Vec2& h = geometry_.cellSize;
  const Vec2 local((x[0] - geometry_.origin[0]) / h[0], (x[1] - geometry_.origin[1]) / h[1]);
  const Vec2 gradient = sideGradient(it->second.sides, local - local.array().floor().matrix(), h);
  // A point where phi barely changes (at the corner of a cell the path only clips, far from it)
  // takes almost none of the band's motion: it stays intact rather than open with H of many cells.
  if (gradient.norm() * std::min(h[0], h[1]) < kLeastGradient) return std::nullopt;
  return PathCrossing{gradient.normalized(), it->second.chord, it->second.scale / gradient.norm()};  // H = scale / |grad phi|
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
    if (const std::optional<Voigt> ahead = averaged(tip + 0.5 * geometry_.averaging * arm.direction, geometry_.averaging, 0.0)) {
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
  // (Most steps of a growing crack hold points at onset beside its path alone: no root to start,
  // and nothing to sort.)
  const auto mayStart = [this](const OnsetCandidate& c) { return !nearPath(c.position) && mayRoot(c); };
  if (std::any_of(candidates.begin(), candidates.end(), mayStart)) {
    std::stable_sort(candidates.begin(), candidates.end(), [](const OnsetCandidate& a, const OnsetCandidate& b) {
      return a.overstress > b.overstress || (a.overstress == b.overstress && a.particle < b.particle);
    });
    std::vector<std::uint8_t> used(candidates.size(), 0);
    for (std::size_t c = 0; c < candidates.size(); ++c) {
      if (used[c] || !mayStart(candidates[c])) continue;
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
      // It lies normal to the first principal direction of the stress of the points near onset
      // around it, where that is tension; else of the candidates' own (docs/model.md, "Crack paths").
      if (const std::optional<Voigt> around = averaged(centre, geometry_.averaging, kRootSharpness);
          around && principalStresses(*around).first > 0.0)
        stress = *around;
      const Vec2 d = perpendicular(principalStresses(stress).firstDirection);
      arms_.push_back({{centre}, d});
      arms_.push_back({{centre}, -d});
      index();
    }
  }
  std::size_t onPath = 0;
  for (const OnsetCandidate& c : candidates) onPath += crossingAt(c.position) ? 1 : 0;
  return onPath;
}

}  // namespace ecm::mpm
