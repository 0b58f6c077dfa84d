#pragma once
// Crack paths (docs/model.md, "Crack paths"): where an enriched point may open its band, with which
// normal and which effective size. A crack starts at a root, where the first points of a region
// reach onset, and grows in two arms, each a polyline from the root to a tip that reaches one
// look-ahead past the tip. A tip moves when a point in its look-ahead opens a band, and turns by
// the kink angle of the maximum hoop stress in the stress averaged ahead of it. A point opens a
// band only in a grid cell whose nodes lie on both sides of a path (band_kinematics.hpp): normal
// to grad phi at the point, so that a rigid motion of one side strains the band alone and nothing
// locks, with an effective size that makes the band dissipate G_F times the path's length. A
// point that reaches onset anywhere else
// stays intact (a candidate: a new root where a crack may start and none is near). Both solvers
// keep one CrackPaths,
// read-only while the points update and grown between updates, in particle order. Under
// CrackPathRule::Free none of it runs.
#include <algorithm>
#include <cstddef>
#include <functional>
#include <cstdint>
#include <optional>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "material/voigt.hpp"
#include "mpm/setup/crack_roots.hpp"
#include "mpm/scene/solver_settings.hpp"

namespace ecm::mpm {

// The grid the paths cut and the rule's lengths (mm; docs/model.md, "Crack paths").
struct CrackPathGeometry {
  Vec2 origin = Vec2::Zero();   // the grid's first node
  Vec2 cellSize = Vec2::Ones();
  double lookAhead = 0.0;  // how far a path reaches past its tip: two cells
  double exclusion = 0.0;  // a new crack starts no nearer than this to a path or another new root
  double averaging = 0.0;  // radius of the stress average that turns a tip
  double smallestKink = 0.0;   // (rad) a tip turns only by a kink at least this large
  double smallestRadius = 0.0; // a path's radius of curvature is at least this (a turn at most turnEvery / it)
  double turnEvery = 0.0;      // a tip's direction is taken again each time it has run this far
  double interiorOverstress = 1.0;  // off a root cell, a crack starts only this far past onset
  int pointsPerCell = 2;            // k: the points a cell is seeded with, k x k (scene.hpp)
  static CrackPathGeometry forGrid(const Vec2& origin, const Vec2& cellSize);
};

// One arm of a crack: a polyline from the crack's root (points[0]) to its tip (back()), and the
// unit direction in which it grows on from the tip. The vertices are where the direction was taken
// (every turnEvery of advance); the last segment runs along `direction` (it is empty just after
// the tip became a vertex).
struct CrackArm {
  std::vector<Vec2> points;
  Vec2 direction = Vec2::UnitY();
};

// A point that reached onset off every path and stayed intact.
struct OnsetCandidate {
  std::size_t particle = 0;
  Vec2 position = Vec2::Zero();
  double overstress = 1.0;        // sqrt(Y / Y_onset) of its elastic stress, Eq. (12) with D = 0
  Voigt stress = Voigt::Zero();   // that stress over the overstress: on the onset surface (MPa)
};

// The points held intact past onset after the last update (tracked paths only; history.csv's
// held_past_onset and held_max_overstress): how much strength the rule lends the bulk off the paths.
struct HeldPoints {
  std::size_t count = 0;
  double largestOverstress = 0.0;  // sqrt(Y / Y_onset), Eq. (12) with D = 0; 0 where none is held
};

// How a point's band opens in a cell of a path's band (band_kinematics.hpp).
struct PathCrossing {
  Vec2 normal = Vec2::UnitX();  // grad phi / |grad phi| at the point
  double chord = 0.0;           // the path's length in the point's cell (mm), look-ahead included
  double effectiveSize = 0.0;   // H = scale / |grad phi| (mm), Eq. (1): the cell's share of G_F times the path's length
};

// The stress, in units of the tensile strength, averaged over the intact points within `radius`
// of a point, each weighted also by (Y / Y_onset)^sharpness, its driving force's share of onset
// (at most 1): 0 for a tip's direction, kRootSharpness for a root's; nullopt where no such point
// is near.
using AveragedStress = std::function<std::optional<Voigt>(const Vec2& at, double radius, double sharpness)>;

// A root's direction is read from the points near onset around it (docs/model.md, "Crack
// paths"): a point at 0.97 of onset's stress counts 0.78 as much as one at onset, one at half
// of it 0.004.
inline constexpr double kRootSharpness = 4.0;

// The direction in which a tip growing along `direction` runs on into the averaged stress `s`
// (in units of the tensile strength) ahead of it: turned by the kink angle of the maximum hoop
// stress (Erdogan and Sih 1963) for the ratio of the shear to the opening stress on its line,
// sigma_nt / max(sigma_nn, 1), which stands for K_II / K_I. Mode I runs straight whatever
// sigma_tt is (a principal direction would not: ahead of a mode-I tip sigma_tt ~ sigma_nn and the
// principal axes swing with any shear). An opening stress below the strength does not drive the
// crack yet and counts as the strength: the ratio of two weak stresses is noise. Unchanged where
// sigma_nn is not tension, and where the field ahead is weak, sigma_nn below
// kLeastSteeringOpening and |sigma_nt| below the strength: the tip then runs into a ligament's
// compression zone, whose shear is the hinge's, not the tip's.
inline constexpr double kLeastSteeringOpening = 0.25;  // of the tensile strength (docs/model.md, "Crack paths")
Vec2 kinkedDirection(const Vec2& direction, const Voigt& s);

class CrackPaths {
 public:
  CrackPaths() = default;  // Free
  // Roots anywhere (unit tests).
  CrackPaths(CrackPathRule rule, const CrackPathGeometry& geometry) : rule_(rule), geometry_(geometry) {}
  // Roots only in `roots` (crack_roots.hpp: the cells on a surface, away from held nodes).
  CrackPaths(CrackPathRule rule, const CrackPathGeometry& geometry, const std::vector<CellIndex>& roots);

  bool tracked() const { return rule_ == CrackPathRule::Tracked; }
  // How a point at x opens its band: normal to grad phi there, with its effective size; nullopt
  // where x is in no band cell, or where |grad phi| is too small to take the band's motion. Pure.
  std::optional<PathCrossing> crossingAt(const Vec2& x) const;
  // Whether a crack may start in the cell that holds x.
  bool mayRootAt(const Vec2& x) const { return !rootCells_ || rootCells_->count(cellOf(x)) > 0; }
  // Whether a held point may start a crack: in a root cell, or elsewhere once it is
  // interiorOverstress past onset.
  bool mayRoot(const OnsetCandidate& c) const { return c.overstress >= geometry_.interiorOverstress || mayRootAt(c.position); }
  // Whether x lies in a cell within the exclusion radius of a path (look-aheads included), counted
  // in whole cells around each segment's cells: where no crack may start.
  bool nearPath(const Vec2& x) const { return near_.count(cellOf(x)) > 0; }

  // After the points' updates, in particle order: each arm whose look-ahead holds a point that
  // opened its band (`opened`, their positions) moves its tip to the farthest such point's
  // projection and, every turnEvery, turns by kinkedDirection() in the stress averaged ahead of
  // it where that kink is at least `smallestKink` (below it the kink is the noise of the
  // particles' stresses: a crack that curves turns once the kink its straight run builds up
  // passes that), by at most turnEvery / smallestRadius; then each candidate (most overstressed
  // first) that may start a crack (mayRoot) farther than `exclusion` from every path starts one
  // at the centre of the cell that holds the overstress-weighted centre of the candidates near it
  // (a crack that starts on a grid line, as on a symmetry plane, would flip between the cells on
  // either side of it at the least turn), normal to the first principal direction of the stress
  // averaged around that centre over the points near onset (kRootSharpness; where that average
  // is tension, else of the candidates' overstress-weighted stress): the points that reach onset
  // first say where a crack starts, all those near onset how it lies (in an explicit step the
  // points of one notch corner can pass onset a step before the other's). Returns how many
  // candidates are now in a crossed cell (they may open a band when their update is taken again).
  std::size_t grow(const std::vector<Vec2>& opened, std::vector<OnsetCandidate> candidates, const AveragedStress& averaged);

  // Notes the points held past onset by the last update (called after every update, grown or not).
  void noteHeld(const std::vector<OnsetCandidate>& candidates) {
    held_ = {candidates.size(), 0.0};
    for (const OnsetCandidate& c : candidates) held_.largestOverstress = std::max(held_.largestOverstress, c.overstress);
  }
  const HeldPoints& held() const { return held_; }

  const std::vector<CrackArm>& arms() const { return arms_; }
  const CrackPathGeometry& geometry() const { return geometry_; }
  CrackPathRule rule() const { return rule_; }
  // The arms as they are (tests, checkpoints).
  void restoreArms(std::vector<CrackArm> arms) {
    arms_ = std::move(arms);
    index();
  }
  // Checkpoints (mpm/output/checkpoint_codec.hpp's Encoder and Decoder): u64 arms, each u64
  // points, f64 x y of each, f64 direction x y.
  template <class Encoder>
  void encode(Encoder& e) const {
    e.count(arms_.size());
    for (const CrackArm& arm : arms_) {
      e.count(arm.points.size());
      for (const Vec2& p : arm.points) e.put(p);
      e.put(arm.direction);
    }
  }
  template <class Decoder>
  void decode(Decoder& d) {
    arms_.assign(d.count(sizeof(std::uint64_t) + 4 * sizeof(double)), CrackArm{});
    const auto vec2 = [&d] {  // (x first: the order of a call's arguments is unspecified)
      const double x = d.template get<double>();
      return Vec2(x, d.template get<double>());
    };
    for (CrackArm& arm : arms_) {
      arm.points.resize(d.count(2 * sizeof(double)));
      for (Vec2& p : arm.points) p = vec2();
      arm.direction = vec2();
    }
    index();
  }

 private:
  using CellKey = std::int64_t;
  CellKey cellOf(const Vec2& x) const;
  // Rebuilds the lookups below from the arms (after every change of them).
  void index();

  CrackPathRule rule_ = CrackPathRule::Free;
  CrackPathGeometry geometry_;
  std::vector<CrackArm> arms_;
  HeldPoints held_;
  // Lookups of the arms, so that a point's query costs no walk over every path: the crossed cells,
  // and the cells within the exclusion radius of a path.
  struct CellBand {
    std::uint8_t sides = 0;  // band_kinematics.hpp's NodeSides
    double chord = 0.0;      // the path's length in the cell (mm)
    double scale = 1.0;      // the level lines' length in the cell over the path's length it was given
  };
  // Below this |grad phi| times the cell size a point stays intact (H over ten cells).
  static constexpr double kLeastGradient = 0.1;
  std::unordered_map<CellKey, CellBand> crossed_;
  std::unordered_set<CellKey> near_;
  // The cells where a crack may start; nullopt: anywhere. Fixed at the start of a run.
  std::optional<std::unordered_set<CellKey>> rootCells_;
};

// The paths of a run of this rule on this grid: none yet, roots anywhere (unit tests).
inline CrackPaths crackPathsFor(CrackPathRule rule, const Vec2& origin, const Vec2& cellSize) {
  return {rule, CrackPathGeometry::forGrid(origin, cellSize)};
}

// The paths of a scene's run: none yet, roots only on the body's surfaces away from held nodes
// (crack_roots.hpp).
CrackPaths crackPathsFor(const Scene& scene, const Particles& particles);

}  // namespace ecm::mpm
