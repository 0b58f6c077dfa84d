#include "mpm/scene/memory_estimate.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>

#include "io/value_error.hpp"
#include "mpm/core/grid.hpp"
#include "mpm/core/particles.hpp"

namespace ecm::mpm {

namespace {

// The area of a shape inside the grid's rectangle (polygons and circles: their bounding boxes',
// an upper bound).
double areaInGrid(const Shape& s, const Vec2& lo, const Vec2& hi) {
  Vec2 a, b;
  switch (s.kind) {
    case ShapeKind::Rectangle: a = s.min, b = s.max; break;
    case ShapeKind::Circle: a = s.center.array() - s.radius, b = s.center.array() + s.radius; break;
    case ShapeKind::Polygon:
      a = b = s.vertices.empty() ? Vec2::Zero() : s.vertices.front();
      for (const Vec2& v : s.vertices) a = a.cwiseMin(v), b = b.cwiseMax(v);
      break;
  }
  const double w = std::min(b[0], hi[0]) - std::max(a[0], lo[0]), h = std::min(b[1], hi[1]) - std::max(a[1], lo[1]);
  const double box = std::max(w, 0.0) * std::max(h, 0.0);
  return s.kind == ShapeKind::Circle ? std::min(box, std::numbers::pi * s.radius * s.radius) : box;
}

std::string gibibytes(std::size_t bytes) {
  std::ostringstream o;
  o.precision(3);
  o << static_cast<double>(bytes) / (1024.0 * 1024.0 * 1024.0) << " GiB";
  return o.str();
}

}  // namespace

MemoryEstimate estimateMemory(const Scene& scene) {
  const Grid& g = scene.grid;
  const Vec2 lo = g.origin, hi = g.origin + g.extent();
  double area = 0.0;
  for (const Body& b : scene.bodies)
    if (!b.subtract) area += areaInGrid(b.shape, lo, hi);
  const double cells = std::min(area / g.cellArea() + 1.0, static_cast<double>(g.cellsX) * g.cellsY);
  const double k = scene.particlesPerCell;
  MemoryEstimate e;
  e.particles = static_cast<std::size_t>(cells * k * k);
  e.nodes = static_cast<std::size_t>(g.nodesX()) * static_cast<std::size_t>(g.nodesY());
  Particles shape;  // the per-particle arrays of this scene (smeared integrity, second bands)
  ParticleFields fields;
  for (const auto& m : scene.materials) fields |= fieldsFor(m);
  shape.resize(1, fields.integrity, fields.secondBand);
  const std::size_t perParticle = shape.bytesPerParticle() + sizeof(std::uint32_t);  // + its slot in the scatter order
  const std::size_t perNode = sizeof(double) + 5 * sizeof(Vec2) + sizeof(std::uint8_t);  // fields, constrained flag
  e.bytes = e.particles * perParticle + e.nodes * perNode;
  return e;
}

std::optional<std::size_t> availableMemory() {
  std::ifstream in("/proc/meminfo");
  std::string key;
  std::size_t kib = 0;
  std::string unit;
  while (in >> key >> kib >> unit)
    if (key == "MemAvailable:") return kib * 1024;
  return std::nullopt;
}

void checkMemory(const Scene& scene) {
  const std::optional<std::size_t> available = availableMemory();
  if (!available) return;
  const MemoryEstimate e = estimateMemory(scene);
  if (e.bytes <= *available) return;
  throw io::ValueError("grid", "the scene needs about " + gibibytes(e.bytes) + " (" + std::to_string(e.particles) +
                                   " particles at most, " + std::to_string(e.nodes) + " grid nodes), the machine has " +
                                   gibibytes(*available) + " available: use a coarser grid, fewer particles per cell "
                                   "or a smaller domain");
}

}  // namespace ecm::mpm
