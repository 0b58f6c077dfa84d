// The crack paths' geometry (mpm/setup/crack_paths.hpp, docs/model.md "Crack paths"): the kink of
// the maximum hoop stress, the cells a path crosses and their effective sizes, roots and tips.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <functional>
#include <set>
#include <utility>

#include "mpm/setup/band_kinematics.hpp"
#include "mpm/setup/crack_paths.hpp"
#include "mpm/setup/crack_roots.hpp"

namespace ecm::mpm {
namespace {

constexpr double kPi = 3.14159265358979323846;

// A stress average that is the same everywhere (units of the tensile strength).
AveragedStress uniform(const Voigt& s) {
  return [s](const Vec2&, double, double) -> std::optional<Voigt> { return s; };
}

CrackPaths unitGridPaths() { return crackPathsFor(CrackPathRule::Tracked, Vec2(0.0, 0.0), Vec2(1.0, 1.0)); }

// A crack growing along +y has n = (-1, 0): sigma_nn = sigma_xx, sigma_nt = -sigma_xy.
TEST(CrackPaths, ModeIRunsStraightWhateverTheStressAlongTheCrack) {
  const Vec2 d(0.0, 1.0);
  for (const double tt : {-3.0, 0.0, 2.0, 5.0}) EXPECT_EQ(kinkedDirection(d, Voigt(2.0, tt, 0.0)), d);
  EXPECT_EQ(kinkedDirection(d, Voigt(-1.0, 0.0, 0.5)), d);  // a closed crack does not turn
}

// Erdogan and Sih (1963): theta = 2 atan((K_I - sqrt(K_I^2 + 8 K_II^2)) / (4 K_II)). K_II / K_I = 1
// gives 2 atan(-1/2) = -53.13 degrees: (0, 1) turns to (sin 53.13, cos 53.13) = (0.8, 0.6).
TEST(CrackPaths, MixedModeKinksByTheMaximumHoopStressAngle) {
  const Vec2 turned = kinkedDirection(Vec2(0.0, 1.0), Voigt(1.0, 0.0, -1.0));
  EXPECT_NEAR(turned[0], 0.8, 1e-12);
  EXPECT_NEAR(turned[1], 0.6, 1e-12);
  // Shear of the other sign turns the other way.
  EXPECT_NEAR(kinkedDirection(Vec2(0.0, 1.0), Voigt(1.0, 0.0, 1.0))[0], -0.8, 1e-12);
}

// Pure mode II: theta -> 2 atan(-1 / sqrt(2)) = -70.53 degrees. An opening stress below the strength
// counts as the strength, so a large shear over a weak opening is nearly that limit, not noise.
TEST(CrackPaths, PureShearKinksBySeventyDegrees) {
  const Vec2 turned = kinkedDirection(Vec2(0.0, 1.0), Voigt(0.01, 0.0, -1e6));
  EXPECT_NEAR(std::atan2(turned[0], turned[1]), 2.0 * std::atan(1.0 / std::sqrt(2.0)), 1e-5);
  // sigma_nt / sigma_nn = 0.1 / 0.3 would kink by 30 degrees; over the strength (1) it is 0.1: 10.8.
  const Vec2 weak = kinkedDirection(Vec2(0.0, 1.0), Voigt(0.3, 0.0, -0.1));
  EXPECT_NEAR(std::atan2(weak[0], weak[1]) * 180.0 / kPi, -2.0 * std::atan((1.0 - std::sqrt(1.08)) / 0.4) * 180.0 / kPi, 1e-9);
}

// A weak field ahead, sigma_nn below a quarter of the strength and |sigma_nt| below the strength
// (a ligament's compression zone near its far edge, docs/model.md, "Crack paths"), does not steer
// the tip; a shear past the strength still does.
TEST(CrackPaths, AWeakFieldAheadDoesNotSteerTheTip) {
  const Vec2 d(0.0, 1.0);
  EXPECT_EQ(kinkedDirection(d, Voigt(0.2, 0.7, -0.15)), d);
  EXPECT_EQ(kinkedDirection(d, Voigt(0.24, 0.0, 0.9)), d);
  EXPECT_NE(kinkedDirection(d, Voigt(0.26, 0.0, -0.15)), d);  // (a kink of 16 degrees)
  EXPECT_NE(kinkedDirection(d, Voigt(0.2, 0.0, -1.5)), d);
}

// A straight path along a grid column through the cells' middles: the band is that column, with the
// path's normal and H = the cell size (Eq. (1), Fig. 2: each cell dissipates G_F times the path's
// length in it).
TEST(CrackPaths, AStraightPathThroughACellGivesTheCellSizeAsEffectiveSize) {
  CrackPaths paths = unitGridPaths();
  paths.restoreArms({{{Vec2(0.5, 0.0), Vec2(0.5, 3.0)}, Vec2(0.0, 1.0)}});
  for (const Vec2& x : {Vec2(0.3, 1.2), Vec2(0.75, 1.75), Vec2(0.25, 2.25)}) {
    const std::optional<PathCrossing> c = paths.crossingAt(x);
    ASSERT_TRUE(c);
    EXPECT_DOUBLE_EQ(c->chord, 1.0);
    EXPECT_NEAR(c->effectiveSize, 1.0, 1e-12);
    EXPECT_DOUBLE_EQ(std::abs(c->normal[0]), 1.0);
  }
  EXPECT_FALSE(paths.crossingAt(Vec2(1.2, 1.2)));   // the next column
  EXPECT_FALSE(paths.crossingAt(Vec2(-0.5, 1.2)));  // the column before
  // The look-ahead (two cells) crosses the cells past the tip: (0.5, 3) to (0.5, 5).
  EXPECT_TRUE(paths.crossingAt(Vec2(0.7, 3.5)));
  EXPECT_TRUE(paths.crossingAt(Vec2(0.7, 4.5)));
  EXPECT_FALSE(paths.crossingAt(Vec2(0.7, 5.5)));
}

TEST(CrackPaths, APathOnAGridLineCrossesTheCellsOnOneSideOnly) {
  CrackPaths paths = unitGridPaths();
  paths.restoreArms({{{Vec2(1.0, 0.0), Vec2(1.0, 3.0)}, Vec2(0.0, 1.0)}});
  EXPECT_TRUE(paths.crossingAt(Vec2(1.5, 1.5)));
  EXPECT_FALSE(paths.crossingAt(Vec2(0.5, 1.5)));
}

// A diagonal through the cells' corners: the cells it crosses and the cells it touches at a node
// are the band (their nodes lie on both sides of it), and at their centres grad phi is along the
// path's normal.
TEST(CrackPaths, ADiagonalPathsBandOpensNormalToIt) {
  CrackPaths paths = unitGridPaths();
  paths.restoreArms({{{Vec2(0.0, 0.0), Vec2(3.0, 3.0)}, Vec2(1.0, 1.0).normalized()}});
  for (const Vec2& x : {Vec2(1.5, 1.5), Vec2(1.5, 0.5)}) {
    const std::optional<PathCrossing> c = paths.crossingAt(x);
    ASSERT_TRUE(c);
    EXPECT_NEAR(std::abs(c->normal.dot(Vec2(1.0, -1.0).normalized())), 1.0, 1e-12);
  }
  EXPECT_FALSE(paths.crossingAt(Vec2(0.5, 1.5)));  // touched at a node on the path, all on one side
  EXPECT_FALSE(paths.crossingAt(Vec2(2.5, 0.5)));
}

// The band's kinematics (mpm/setup/band_kinematics.hpp): moving every grid node on one side of a
// path rigidly by u (translation, or rotation about the tip) strains no point outside the band, and
// each point inside it only in the components of its own normal: sym(a (x) n) for some a, so that
// t.eps.t = 0 along t perpendicular to n. A band that opens normal to n takes that strain whole:
// nothing locks, at any angle to the grid, round a kink, or across the root of two arms. (With the
// path's own normal a staircase of cells held the jump: checked at the end.)
Voigt strainAt(const Vec2& x, const std::function<Vec2(const Vec2&)>& nodal) {
  const Vec2 lo(std::floor(x[0]), std::floor(x[1]));
  const Vec2 l = x - lo;
  const std::array<Vec2, 4> node{lo, lo + Vec2(1, 0), lo + Vec2(0, 1), lo + Vec2(1, 1)};
  const std::array<Vec2, 4> g{Vec2(-(1 - l[1]), -(1 - l[0])), Vec2(1 - l[1], -l[0]), Vec2(-l[1], 1 - l[0]), Vec2(l[1], l[0])};
  Eigen::Matrix2d grad = Eigen::Matrix2d::Zero();
  for (std::size_t k = 0; k < 4; ++k) grad += nodal(node[k]) * g[k].transpose();
  return Voigt(grad(0, 0), grad(1, 1), grad(0, 1) + grad(1, 0));
}

TEST(CrackPaths, ARigidMotionOfOneSideStrainsOnlyTheBandAlongItsNormal) {
  std::srand(5);
  int lockedWithThePathsNormal = 0;
  for (int k = 0; k < 100; ++k) {
    const double angle = 2.0 * kPi * std::rand() / RAND_MAX, turn = 0.6 * (std::rand() / double(RAND_MAX) - 0.5);
    const Vec2 d(std::cos(angle), std::sin(angle)), d2(std::cos(angle + turn), std::sin(angle + turn));
    const Vec2 root = Vec2(10.0, 10.0) + Vec2(std::rand(), std::rand()) / double(RAND_MAX);
    CrackPaths paths = unitGridPaths();
    // Two arms from one root, one of them kinked (as grown): root - 3 d - 3 d + 4 d2 ... and -d.
    paths.restoreArms({{{root, root + 3.0 * d, root + 6.0 * d}, d2}, {{root, root - 5.0 * d}, -d}});
    // The nodes on the left of the crack (arm 0's polyline) move by a rigid motion.
    std::vector<Vec2> line = paths.arms()[0].points;
    line.push_back(line.back() + paths.geometry().lookAhead * d2);
    std::vector<Vec2> back{root - (5.0 + paths.geometry().lookAhead) * d, root};
    const Vec2 u(0.3, -0.7);
    const double spin = 0.05;
    const auto nodal = [&](const Vec2& x) -> Vec2 {
      // which side: of the arm whose segments are nearer (the crack is the two arms end to end)
      const bool left = (x - root).dot(d) >= 0.0 ? onLeftOf(line, x) : onLeftOf(back, x);
      const Vec2 r = x - root;
      return left ? Vec2(u + spin * Vec2(-r[1], r[0])) : Vec2::Zero();
    };
    for (double x = 2.25; x < 19.0; x += 0.5)
      for (double y = 2.25; y < 19.0; y += 0.5) {
        const Vec2 p(x, y);
        // (beyond the paths' ends the side is not the crack's: away from them only)
        if ((p - back.front()).dot(d) < 1.5 || (line.back() - p).dot(d2) < 1.5) continue;
        const Voigt e = strainAt(p, nodal);
        const std::optional<PathCrossing> c = paths.crossingAt(p);
        if (!c) {
          EXPECT_LT(e.cwiseAbs().maxCoeff(), 1e-12) << "k " << k << " at " << x << ", " << y;
          continue;
        }
        const Vec2 t(-c->normal[1], c->normal[0]);
        const double along = t[0] * t[0] * e[0] + t[1] * t[1] * e[1] + t[0] * t[1] * e[2];
        EXPECT_LT(std::abs(along), 1e-12) << "k " << k << " at " << x << ", " << y;
        const Vec2 n(-(line[1] - line[0]).normalized()[1], (line[1] - line[0]).normalized()[0]);
        const Vec2 tp(-n[1], n[0]);
        if (std::abs(tp[0] * tp[0] * e[0] + tp[1] * tp[1] * e[1] + tp[0] * tp[1] * e[2]) > 1e-3) ++lockedWithThePathsNormal;
      }
  }
  // With the path's own normal, most of the band's points would strain along the crack: locking.
  EXPECT_GT(lockedWithThePathsNormal, 1000);
}

// Over many straight paths at random angles and offsets, the band dissipates G_F times the path's
// length: the sum over the points (2 x 2 a cell, as seeded) of V / H is the path's length within
// 0.2 % (a sliver of path at its ends, in a cell with no band cell around it, is lost), while the level lines of phi alone would give up to 20 % more across the grid's diagonal.
TEST(CrackPaths, TheBandDissipatesForThePathsLength) {
  CrackPaths paths = unitGridPaths();
  std::srand(7);
  for (int k = 0; k < 200; ++k) {
    const double angle = kPi * std::rand() / RAND_MAX, x0 = 10.0 + std::rand() / double(RAND_MAX);
    const Vec2 d(std::cos(angle), std::sin(angle));
    const Vec2 a = Vec2(x0, 10.5) - 6.0 * d, b = Vec2(x0, 10.5) + 4.0 * d;
    paths.restoreArms({{{a, b}, d}});
    // The cells whose centres lie within the middle 6 of the path's 12 (look-ahead included), away
    // from its ends: their points' shares against the path's length in them.
    double share = 0.0, length = 0.0;
    for (int i = 0; i < 22; ++i)
      for (int j = 0; j < 22; ++j) {
        for (const Vec2& at : {Vec2(0.25, 0.25), Vec2(0.75, 0.25), Vec2(0.25, 0.75), Vec2(0.75, 0.75)})
          if (const std::optional<PathCrossing> c = paths.crossingAt(Vec2(i, j) + at)) {
            share += 0.25 / c->effectiveSize;
            if (at == Vec2(0.25, 0.25)) length += c->chord;
          }
      }
    EXPECT_NEAR(length, 12.0, 1e-9);
    EXPECT_NEAR(share / length, 1.0, 2e-3) << "angle " << angle * 180.0 / kPi;
  }
}

// Two symmetric points at onset start one crack at the centre of their cell, normal to their
// stress, in two arms; a point within the exclusion radius of it starts none.
TEST(CrackPaths, OnsetStartsOneCrackAtTheCentreOfItsCell) {
  CrackPaths paths = unitGridPaths();
  const Voigt s(3.0, 0.0, 0.0);
  std::vector<OnsetCandidate> held{{0, Vec2(0.3, 0.6), 1.0, s}, {1, Vec2(0.7, 0.6), 1.0, s}};
  EXPECT_EQ(paths.grow({}, held, uniform(Voigt::Zero())), 2u);
  ASSERT_EQ(paths.arms().size(), 2u);
  EXPECT_EQ(paths.arms()[0].points[0], Vec2(0.5, 0.5));
  EXPECT_EQ(paths.arms()[0].direction, Vec2(0.0, 1.0));
  EXPECT_EQ(paths.arms()[1].direction, Vec2(0.0, -1.0));
  // A point at onset within the exclusion radius of that crack (beside it) stays held.
  EXPECT_EQ(paths.grow({}, {{2, Vec2(3.0, 0.6), 1.5, s}}, uniform(Voigt::Zero())), 0u);
  EXPECT_EQ(paths.arms().size(), 2u);
  // A held point on the path starts nothing and is counted: it opens its band when its update
  // is taken again (the implicit solver repeats the load step for it).
  EXPECT_EQ(paths.grow({}, {{4, Vec2(0.4, 0.4), 1.2, s}}, uniform(Voigt::Zero())), 1u);
  EXPECT_EQ(paths.arms().size(), 2u);
  EXPECT_TRUE(paths.nearPath(Vec2(0.5 + paths.geometry().exclusion, 0.5)));
  // A second region of onset beyond the exclusion radius starts a crack of its own.
  const double far = paths.geometry().exclusion + 2.0;
  EXPECT_FALSE(paths.nearPath(Vec2(0.5 + far, 0.5)));
  EXPECT_EQ(paths.grow({}, {{3, Vec2(0.5 + far, 0.5), 1.1, s}}, uniform(Voigt::Zero())), 1u);
  EXPECT_EQ(paths.arms().size(), 4u);
}

// A crack lies as the stress averaged around its root asks, where that is tension, not as the
// few points that passed onset first: in an explicit step one notch corner's points, whose shear
// tilted the beam's crack by 17 degrees (docs/model.md, "Crack paths").
TEST(CrackPaths, ACrackLiesNormalToTheStressAveragedAroundItsRoot) {
  CrackPaths paths = unitGridPaths();
  // One candidate, its stress tilted 22.5 degrees (sigma_xx = 1, sigma_xy = 0.5); the field around
  // it pulls in x alone: the crack runs in y.
  const std::vector<OnsetCandidate> corner{{0, Vec2(0.3, 0.6), 1.0, Voigt(1.0, 0.0, 0.5)}};
  EXPECT_EQ(paths.grow({}, corner, uniform(Voigt(0.8, 0.1, 0.0))), 1u);
  ASSERT_EQ(paths.arms().size(), 2u);
  EXPECT_EQ(paths.arms()[0].direction, Vec2(0.0, 1.0));
  // Where the field around it is not tension, the candidate's own stress says how it lies.
  CrackPaths compressed = unitGridPaths();
  compressed.grow({}, corner, uniform(Voigt(-1.0, -0.5, 0.0)));
  ASSERT_EQ(compressed.arms().size(), 2u);
  const Vec2 tilted = compressed.arms()[0].direction;  // normal to (cos 22.5, sin 22.5)
  EXPECT_NEAR(std::abs(tilted.dot(Vec2(std::cos(kPi / 8.0), std::sin(kPi / 8.0)))), 0.0, 1e-12);
}

// A band opening in a tip's look-ahead moves the tip to it; the tip turns only by a kink of at
// least smallestKink (5 degrees), and by at most turnEvery / smallestRadius.
TEST(CrackPaths, ATipMovesToTheBandsThatOpenAheadOfItAndTurnsBeyondTheNoise) {
  CrackPathGeometry g = CrackPathGeometry::forGrid(Vec2::Zero(), Vec2::Ones());
  g.smallestRadius = 0.1;  // (no bound on the turn here: the next test bounds it)
  CrackPaths paths(CrackPathRule::Tracked, g);
  paths.restoreArms({{{Vec2(0.5, 0.5)}, Vec2(0.0, 1.0)}});
  // 0.3 past the tip: the tip moves, below turnEvery (half a cell) the direction is not taken again.
  paths.grow({Vec2(0.6, 0.8)}, {}, uniform(Voigt(1.0, 0.0, -1.0)));
  ASSERT_EQ(paths.arms()[0].points.size(), 2u);
  EXPECT_NEAR(paths.arms()[0].points[1][1], 0.8, 1e-12);
  EXPECT_EQ(paths.arms()[0].direction, Vec2(0.0, 1.0));
  // 0.5 further (0.8 from the vertex): the tip becomes a vertex, the kink of 2.9 degrees is noise.
  paths.grow({Vec2(0.4, 1.3)}, {}, uniform(Voigt(2.0, 1.0, -0.05)));
  ASSERT_EQ(paths.arms()[0].points.size(), 3u);
  EXPECT_NEAR(paths.arms()[0].points[2][1], 1.3, 1e-12);
  EXPECT_EQ(paths.arms()[0].direction, Vec2(0.0, 1.0));
  paths.grow({Vec2(0.5, 2.0)}, {}, uniform(Voigt(1.0, 0.0, -1.0)));  // 53 degrees
  EXPECT_NEAR(paths.arms()[0].direction[0], 0.8, 1e-12);
  // A band that opens behind the tip or beside the look-ahead does not move it.
  const std::size_t vertices = paths.arms()[0].points.size();
  const Vec2 tip = paths.arms()[0].points.back();
  paths.grow({Vec2(0.5, 1.0), Vec2(3.0, 2.5)}, {}, uniform(Voigt::Zero()));
  EXPECT_EQ(paths.arms()[0].points.size(), vertices);
  EXPECT_EQ(paths.arms()[0].points.back(), tip);
}

// A path curves no tighter than smallestRadius (10 mm, 3 cells at least): in a field that asks a kink
// of 53 degrees at every vertex, each turnEvery of advance turns the tip by turnEvery /
// smallestRadius, and the path runs on a polygon of that radius.
TEST(CrackPaths, APathCurvesNoTighterThanItsSmallestRadius) {
  CrackPaths paths = unitGridPaths();
  const CrackPathGeometry& g = paths.geometry();
  EXPECT_DOUBLE_EQ(g.smallestRadius, 10.0);  // (unit cells: 10 mm)
  EXPECT_DOUBLE_EQ(g.averaging, 20.0);
  paths.restoreArms({{{Vec2(0.5, 0.5)}, Vec2(0.0, 1.0)}});
  double heading = 0.0;  // atan2(x, y): clockwise from +y (this shear turns the path the other way)
  for (int k = 0; k < 6; ++k) {
    const CrackArm& arm = paths.arms()[0];
    // A stress that asks the same 53-degree kink of the arm's current line (sigma_nn = 1 = -sigma_nt).
    const Vec2 d = arm.direction, n(-d[1], d[0]);
    const Eigen::Matrix2d s = n * n.transpose() - (n * d.transpose() + d * n.transpose());
    paths.grow({arm.points.back() + 0.6 * d}, {}, uniform(Voigt(s(0, 0), s(1, 1), s(0, 1))));
    heading -= g.turnEvery / g.smallestRadius;
    EXPECT_NEAR(std::atan2(paths.arms()[0].direction[0], paths.arms()[0].direction[1]), heading, 1e-9) << k;
  }
}

// A point opens anywhere in a cell the look-ahead crosses, so up to a cell's diagonal past the
// look-ahead's end; it moves the tip to that end (a tip left short of it could find no new cell
// in its look-ahead, and the crack would stall: seen on the DEN's inclined cracks).
TEST(CrackPaths, ABandOpeningPastTheLookAheadsEndMovesTheTipToThatEnd) {
  CrackPaths paths = unitGridPaths();
  const double lookAhead = paths.geometry().lookAhead;  // two cells
  paths.restoreArms({{{Vec2(0.5, 0.5)}, Vec2(0.0, 1.0)}});
  paths.grow({Vec2(0.6, 0.5 + lookAhead + 0.4)}, {}, uniform(Voigt::Zero()));  // 0.4 past the look-ahead's end
  ASSERT_EQ(paths.arms()[0].points.size(), 3u);  // (past half a cell: the tip became a vertex)
  EXPECT_NEAR(paths.arms()[0].points.back()[1], 0.5 + lookAhead, 1e-12);
  // Farther than the look-ahead and a diagonal: not this arm's band.
  paths.grow({Vec2(0.5, 0.5 + 2.0 * lookAhead + std::sqrt(2.0) + 0.01)}, {}, uniform(Voigt::Zero()));
  EXPECT_NEAR(paths.arms()[0].points.back()[1], 0.5 + lookAhead, 1e-12);
}

// Where a crack may start: cells on a surface of the body (an edge, a notch's face), none within
// the exclusion radius of a box of held nodes, none inside the body.
TEST(CrackRoots, CracksStartOnSurfacesAwayFromHeldNodes) {
  Scene scene;
  scene.grid.origin = Vec2::Zero();
  scene.grid.cellSize = Vec2::Ones();
  scene.grid.cellsX = 12;
  scene.grid.cellsY = 8;
  Particles particles;
  for (int j = 0; j < 8; ++j)
    for (int i = 0; i < 12; ++i) {
      if (i == 6 && j < 3) continue;  // a notch one cell wide, three deep, from the bottom edge
      for (const double dx : {0.25, 0.75})
        for (const double dy : {0.25, 0.75}) {
          particles.position.push_back(Vec2(i + dx, j + dy));
          particles.origin.push_back(Vec2(i + dx, j + dy));
          particles.material.push_back(0);
        }
    }
  scene.conditions.push_back(NodeCondition::fixed("clamp", Box{Vec2(-1.0, 7.9), Vec2(3.0, 9.0)}));
  const std::vector<CellIndex> roots = rootCells(scene, particles, 1.5);
  std::set<std::pair<long, long>> at;
  for (const CellIndex& c : roots) at.insert({c.i, c.j});
  EXPECT_TRUE(at.count({5, 1}));   // the notch's left face
  EXPECT_TRUE(at.count({7, 2}));   // its right face
  EXPECT_TRUE(at.count({6, 3}));   // its tip
  EXPECT_TRUE(at.count({11, 4}));  // the right edge
  EXPECT_TRUE(at.count({0, 3}));   // the left edge, 4.5 below the clamp
  EXPECT_FALSE(at.count({3, 4}));  // inside
  EXPECT_FALSE(at.count({9, 5}));
  EXPECT_FALSE(at.count({0, 7}));  // beside the clamp
  EXPECT_FALSE(at.count({3, 7}));  // 0.64 from it
  EXPECT_FALSE(at.count({0, 6}));  // 1.4 below it
  EXPECT_TRUE(at.count({4, 7}));   // 1.55 from it
  EXPECT_FALSE(at.count({6, 0}));  // the notch holds no points
}

// Held off a root cell, a point starts a crack only once it is interiorOverstress past onset.
TEST(CrackRoots, APointInsideTheBodyStartsACrackOnlyWellPastOnset) {
  const CrackPathGeometry g = CrackPathGeometry::forGrid(Vec2::Zero(), Vec2::Ones());
  CrackPaths paths(CrackPathRule::Tracked, g, {CellIndex{0, 0}});
  EXPECT_TRUE(paths.mayRootAt(Vec2(0.5, 0.5)));
  EXPECT_FALSE(paths.mayRootAt(Vec2(30.5, 30.5)));
  const Voigt s(1.0, 0.0, 0.0);
  const double below = 0.99 * g.interiorOverstress;
  EXPECT_EQ(paths.grow({}, {{0, Vec2(30.5, 30.5), below, s}}, uniform(Voigt::Zero())), 0u);
  EXPECT_TRUE(paths.arms().empty());
  EXPECT_EQ(paths.grow({}, {{0, Vec2(30.5, 30.5), g.interiorOverstress, s}}, uniform(Voigt::Zero())), 1u);
  EXPECT_EQ(paths.arms().size(), 2u);
  // On a root cell, onset is enough.
  EXPECT_EQ(paths.grow({}, {{1, Vec2(0.5, 0.5), 1.0, s}}, uniform(Voigt::Zero())), 1u);
  EXPECT_EQ(paths.arms().size(), 4u);
}

// Free: no paths, nothing grows.
TEST(CrackPaths, TheFreeRuleTracksNothing) {
  CrackPaths paths;
  EXPECT_FALSE(paths.tracked());
  EXPECT_EQ(paths.grow({Vec2(0.0, 0.0)}, {{0, Vec2(0.0, 0.0), 2.0, Voigt(3.0, 0.0, 0.0)}}, uniform(Voigt::Zero())), 0u);
  EXPECT_TRUE(paths.arms().empty());
}

}  // namespace
}  // namespace ecm::mpm
