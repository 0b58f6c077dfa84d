#pragma once
// The kinematics of a band of grid cells that a crack path crosses (docs/model.md, "Crack paths",
// "Where a band may open"). Label each node of a crossed cell by the side of the path it lies on
// (1 on the left, 0 on the right) and let phi be the shape functions' interpolation of those
// labels: the body on one side moving rigidly by u relative to the other gives each point of the
// band the strain sym(u (x) grad phi), and nothing outside it. A band that opens normal to
// grad phi, with H = 1 / |grad phi|, takes that motion whole, with no strain left in its bulk: the
// band opens as freely across the grid as along it. (A path's own normal would not: in a
// staircase of cells crossed by an inclined path grad phi is mostly along a grid axis, and a band
// normal to the path held the jump.) Pure functions, linear shape functions on one cell.
#include <cstdint>
#include <vector>

#include "material/voigt.hpp"

namespace ecm::mpm {

// Which of a cell's four nodes lie on the left of a path: bit 0 the node at the cell's lower left,
// bit 1 lower right, bit 2 upper left, bit 3 upper right.
using NodeSides = std::uint8_t;

// Whether x lies on the left of the polyline `path` (or on it), the path running on past both ends
// along its end segments: the sign of (x - c) . n at the closest point c, n the left normal of
// that segment (at a vertex, the sum of its two segments' normals). An empty or pointlike path
// has nothing on its left.
bool onLeftOf(const std::vector<Vec2>& path, const Vec2& x);

// The sides of the nodes of the cell whose lower-left node is `lo`.
NodeSides nodeSides(const std::vector<Vec2>& path, const Vec2& lo, const Vec2& cellSize);

// Whether a cell's nodes lie on both sides: the cell is part of the band.
inline bool straddles(NodeSides s) { return s != 0 && s != 0xF; }

// grad phi at `local` = ((x - lo) / h_x, (y - lo) / h_y) in [0, 1]^2 (1 / mm).
Vec2 sideGradient(NodeSides s, const Vec2& local, const Vec2& cellSize);

// The integral of |grad phi| over the cell (mm), taken at the k x k points the cell is seeded with
// and over those where |grad phi| times the cell size is at least `leastGradient` (the others stay
// intact): by the co-area formula, the mean length of the level lines of phi in the cell, the
// crack length for which its points' bands, with H = 1 / |grad phi|, would dissipate G_F.
double sideGradientIntegral(NodeSides s, const Vec2& cellSize, int pointsPerCell, double leastGradient);

}  // namespace ecm::mpm
