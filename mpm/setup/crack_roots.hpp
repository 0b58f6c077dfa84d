#pragma once
// Where a crack may start under tracked crack paths (docs/model.md, "Crack paths", roots): in a
// grid cell on a surface of the body (a cell holding points some of whose eight neighbours hold
// none of the same material: a free edge, a notch's face, an interface with another material),
// and not within `exclusion` of a box of nodes that the scene holds or moves (a condition or a
// platen: with rigid, perfectly bonded supports the stress at the end of a held edge is singular
// in the model, not in the test). Pure: read from the points' seeded positions, so a restarted
// run finds the same cells.
#include <vector>

#include "mpm/core/grid.hpp"
#include "mpm/core/particles.hpp"
#include "mpm/scene/scene.hpp"

namespace ecm::mpm {

struct CellIndex {
  long i = 0, j = 0;  // the cell [origin + (i, j) h, origin + (i + 1, j + 1) h)
};

std::vector<CellIndex> rootCells(const Scene& scene, const Particles& particles, double exclusion);

}  // namespace ecm::mpm
