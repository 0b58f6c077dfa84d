#pragma once
// Shapes of the scene (rectangles, polygons, circles) and axis-aligned boxes for node and
// particle sets. Plain data; contains() is the only behaviour.
#include <vector>

#include "material/voigt.hpp"

namespace ecm::mpm {

// Closed box [min, max] (mm), used to pick node and particle sets.
struct Box {
  Vec2 min = Vec2::Zero();
  Vec2 max = Vec2::Zero();
  // With a tolerance (mm) so that nodes lying on the box edge are inside despite round-off.
  bool contains(const Vec2& p, double tolerance = 0.0) const {
    return p[0] >= min[0] - tolerance && p[0] <= max[0] + tolerance && p[1] >= min[1] - tolerance &&
           p[1] <= max[1] + tolerance;
  }
};

enum class ShapeKind { Rectangle, Polygon, Circle };

struct Shape {
  ShapeKind kind = ShapeKind::Rectangle;
  Vec2 min = Vec2::Zero(), max = Vec2::Zero();  // rectangle (mm)
  std::vector<Vec2> vertices;                   // polygon, either orientation, not self-intersecting (mm)
  Vec2 center = Vec2::Zero();                   // circle (mm)
  double radius = 0.0;                          // circle (mm)

  static Shape rectangle(const Vec2& lo, const Vec2& hi) { return {ShapeKind::Rectangle, lo, hi, {}, {}, 0.0}; }
  static Shape polygon(std::vector<Vec2> v) { return {ShapeKind::Polygon, {}, {}, std::move(v), {}, 0.0}; }
  static Shape circle(const Vec2& c, double r) { return {ShapeKind::Circle, {}, {}, {}, c, r}; }

  // Point-in-shape; points exactly on an edge count as inside for rectangles and circles.
  bool contains(const Vec2& p) const;
  void validate() const;  // throws std::invalid_argument
};

// A shape that adds material (material id >= 0) or removes it (subtract: notches, holes).
// Later bodies override earlier ones at a point.
struct Body {
  Shape shape;
  int material = 0;                       // index into Scene::materials
  bool subtract = false;
  Vec2 initialVelocity = Vec2::Zero();    // mm/s
  int item = -1;  // its item in a scene file's bodies list (for messages); -1: built in code
};

}  // namespace ecm::mpm
