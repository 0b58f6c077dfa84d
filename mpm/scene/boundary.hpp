#pragma once
// Boundary conditions and loads on node or particle sets picked by boxes (plain data).
#include <algorithm>
#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "mpm/scene/geometry.hpp"
#include "mpm/scene/time_function.hpp"

namespace ecm::mpm {

enum class Prescribed {
  Free,          // component not constrained
  Fixed,         // v = 0
  Velocity,      // v = history(t)                      (mm/s)
  Displacement,  // u = history(t), imposed as v = (u(t + dt) - u(t)) / dt  (mm)
};

struct ComponentCondition {
  Prescribed kind = Prescribed::Free;
  TimeFunction history;  // unused for Free and Fixed
};

// Velocity field v(x, t) = scale(t) * gradient * (x - origin) prescribed on both components
// (drives a homogeneous deformation through the grid).
struct AffineVelocity {
  Mat2 gradient = Mat2::Zero();  // 1/s
  Vec2 origin = Vec2::Zero();    // mm
  TimeFunction scale = TimeFunction::hold(1.0);
};

// Constraint of the grid nodes inside `box`. The reaction (the force the constraint exerts,
// N) is summed over the nodes every step.
struct NodeCondition {
  std::string name;
  Box box;
  std::array<ComponentCondition, 2> component;  // x, y
  std::optional<AffineVelocity> field;           // if set, overrides `component`

  static NodeCondition fixed(std::string name, Box b, bool x = true, bool y = true) {
    NodeCondition c{std::move(name), b, {}, std::nullopt};
    if (x) c.component[0].kind = Prescribed::Fixed;
    if (y) c.component[1].kind = Prescribed::Fixed;
    return c;
  }
};

// A condition that moves its nodes (a displacement or velocity history, or an affine field), as
// opposed to one that only holds them: its reaction is the structure's load.
inline bool isDriven(const NodeCondition& c) {
  if (c.field) return true;
  for (const auto& k : c.component)
    if (k.kind == Prescribed::Velocity || k.kind == Prescribed::Displacement) return true;
  return false;
}

// The component a driven condition loads along (the first prescribed one), for plots and peaks.
inline int drivenComponent(const NodeCondition& c) {
  const auto driven = [](const ComponentCondition& k) { return k.kind == Prescribed::Velocity || k.kind == Prescribed::Displacement; };
  return driven(c.component[1]) && !driven(c.component[0]) ? 1 : 0;
}

// The index of the condition called `name`, if there is one.
inline std::optional<std::size_t> findCondition(const std::vector<NodeCondition>& conditions, std::string_view name) {
  const auto it = std::find_if(conditions.begin(), conditions.end(), [&](const NodeCondition& c) { return c.name == name; });
  if (it == conditions.end()) return std::nullopt;
  return static_cast<std::size_t>(it - conditions.begin());
}

enum class LoadTarget { Nodes, Particles };
// The scene spelling (`on: particles | nodes`).
constexpr const char* toString(LoadTarget t) { return t == LoadTarget::Nodes ? "nodes" : "particles"; }

// Total force `force * history(t)` (N) spread equally over the nodes or particles in `box`.
struct Load {
  std::string name;
  Box box;
  LoadTarget target = LoadTarget::Particles;
  Vec2 force = Vec2::Zero();  // N (thickness included: the total on the set)
  TimeFunction history = TimeFunction::hold(1.0);
};

}  // namespace ecm::mpm
