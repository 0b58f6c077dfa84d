#pragma once
// The uniform Cartesian background grid: nodes addressed by index arithmetic (no search), and
// the nodal fields stored one array per field.
#include <cstdint>
#include <vector>

#include "material/voigt.hpp"

namespace ecm::mpm {

struct Grid {
  Vec2 origin = Vec2::Zero();     // position of node (0, 0) (mm)
  Vec2 cellSize = Vec2::Ones();   // (mm)
  int cellsX = 1, cellsY = 1;

  int nodesX() const { return cellsX + 1; }
  int nodesY() const { return cellsY + 1; }
  int nodeCount() const { return nodesX() * nodesY(); }
  int node(int i, int j) const { return j * nodesX() + i; }
  Vec2 nodePosition(int n) const {
    return origin + Vec2((n % nodesX()) * cellSize[0], (n / nodesX()) * cellSize[1]);
  }
  double cellArea() const { return cellSize[0] * cellSize[1]; }
  Vec2 extent() const { return Vec2(cellsX * cellSize[0], cellsY * cellSize[1]); }
  void validate() const;  // throws std::invalid_argument
};

// Nodal fields. `force` holds the internal forces of the step (N), `externalForce` those of
// loads and gravity, `velocity` the updated v^{n+1} after boundary conditions,
// `velocityChange` v^{n+1} - v^n (for FLIP).
struct GridFields {
  std::vector<double> mass;           // t
  std::vector<Vec2> momentum;         // t mm/s
  std::vector<Vec2> force;            // N, internal
  std::vector<Vec2> externalForce;    // N, loads and gravity
  std::vector<Vec2> velocity;         // mm/s
  std::vector<Vec2> velocityChange;   // mm/s

  void resize(int n);
};

}  // namespace ecm::mpm
