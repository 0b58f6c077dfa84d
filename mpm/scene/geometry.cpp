#include "mpm/scene/geometry.hpp"

#include <cmath>
#include <stdexcept>

namespace ecm::mpm {

bool Shape::contains(const Vec2& p) const {
  switch (kind) {
    case ShapeKind::Rectangle: return p[0] >= min[0] && p[0] <= max[0] && p[1] >= min[1] && p[1] <= max[1];
    case ShapeKind::Circle: return (p - center).squaredNorm() <= radius * radius;
    case ShapeKind::Polygon: {
      // Even-odd crossing rule along +x.
      bool inside = false;
      const std::size_t n = vertices.size();
      for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
        const Vec2& a = vertices[i];
        const Vec2& b = vertices[j];
        if ((a[1] > p[1]) != (b[1] > p[1])) {
          const double x = a[0] + (p[1] - a[1]) * (b[0] - a[0]) / (b[1] - a[1]);
          if (p[0] < x) inside = !inside;
        }
      }
      return inside;
    }
  }
  return false;
}

void Shape::validate() const {
  switch (kind) {
    case ShapeKind::Rectangle:
      if (!(max[0] > min[0] && max[1] > min[1])) throw std::invalid_argument("rectangle needs max > min in x and y");
      break;
    case ShapeKind::Circle:
      if (!(radius > 0.0)) throw std::invalid_argument("circle radius must be > 0 mm");
      break;
    case ShapeKind::Polygon: {
      if (vertices.size() < 3) throw std::invalid_argument("polygon needs at least 3 vertices");
      double area2 = 0.0;
      for (std::size_t i = 0, j = vertices.size() - 1; i < vertices.size(); j = i++)
        area2 += vertices[j][0] * vertices[i][1] - vertices[i][0] * vertices[j][1];
      if (!(std::abs(area2) > 0.0)) throw std::invalid_argument("polygon has zero area");
      break;
    }
  }
}

}  // namespace ecm::mpm
