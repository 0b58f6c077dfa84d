#include "mpm/core/grid.hpp"

#include <stdexcept>

namespace ecm::mpm {

void Grid::validate() const {
  if (!(cellSize[0] > 0.0 && cellSize[1] > 0.0)) throw std::invalid_argument("grid cell size must be > 0 mm");
  if (cellsX < 1 || cellsY < 1) throw std::invalid_argument("grid needs at least one cell in x and y");
  if (static_cast<long long>(cellsX + 1) * (cellsY + 1) > 2'000'000'000LL)
    throw std::invalid_argument("grid has too many nodes for 32-bit node indices");
}

void GridFields::resize(int n) {
  const auto s = static_cast<std::size_t>(n);
  mass.assign(s, 0.0);
  momentum.assign(s, Vec2::Zero());
  force.assign(s, Vec2::Zero());
  externalForce.assign(s, Vec2::Zero());
  velocity.assign(s, Vec2::Zero());
  velocityChange.assign(s, Vec2::Zero());
}

}  // namespace ecm::mpm
