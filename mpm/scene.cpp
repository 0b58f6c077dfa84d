#include "mpm/scene.hpp"

#include <cmath>
#include <stdexcept>

namespace ecm::mpm {

const char* toString(UpdateScheme s) {
  switch (s) {
    case UpdateScheme::USF: return "usf";
    case UpdateScheme::USL: return "usl";
    case UpdateScheme::MUSL: return "musl";
  }
  return "?";
}

namespace {
[[noreturn]] void fail(const std::string& what) { throw std::invalid_argument(what); }

void checkHistory(const TimeFunction& h, const std::string& where) {
  try {
    h.validate();
  } catch (const std::invalid_argument& e) {
    fail(where + ": " + e.what());
  }
}
}  // namespace

void Scene::validate() const {
  grid.validate();
  if (!(thickness > 0.0)) fail("thickness must be > 0 mm");
  if (materials.empty()) fail("the scene has no materials");
  if (materials.size() > 255) fail("at most 255 materials");
  for (const auto& m : materials) {
    m.validate();
    if (!(m.density > 0.0)) fail("material '" + m.name + "': MPM needs density > 0 (t/mm^3)");
    if (m.elastic.hypothesis != materials.front().elastic.hypothesis)
      fail("material '" + m.name + "': all materials must share plane stress or plane strain");
  }
  if (bodies.empty()) fail("the scene has no bodies");
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const Body& b = bodies[i];
    try {
      b.shape.validate();
    } catch (const std::invalid_argument& e) {
      fail("body " + std::to_string(i) + ": " + e.what());
    }
    if (!b.subtract && (b.material < 0 || b.material >= static_cast<int>(materials.size())))
      fail("body " + std::to_string(i) + ": material index " + std::to_string(b.material) + " out of range");
    if (!b.initialVelocity.allFinite()) fail("body " + std::to_string(i) + ": initial velocity must be finite");
  }
  if (particlesPerCell < 1 || particlesPerCell > 8) fail("particles per cell k must be in [1, 8]");
  if (!(solver.cfl > 0.0 && solver.cfl <= 1.0))
    fail("CFL number " + std::to_string(solver.cfl) + " outside (0, 1]: the explicit step would be unstable");
  if (!(solver.flip >= 0.0 && solver.flip <= 1.0)) fail("PIC/FLIP blend must be in [0, 1]");
  if (!(solver.damping.local >= 0.0 && solver.damping.local < 1.0)) fail("local damping must be in [0, 1)");
  if (!(solver.damping.viscous >= 0.0 && std::isfinite(solver.damping.viscous))) fail("viscous damping must be >= 0 (1/s)");
  if (!solver.gravity.allFinite()) fail("gravity must be finite");
  if (solver.effectiveSize == EffectiveSizeRule::Fixed) fail("effective size rule must be sqrt or oriented");
  if (solver.substepLevels < 0 || solver.substepLevels > 12) fail("sub-step levels must be in [0, 12]");
  if (solver.shapeFunction == ShapeFunction::UGimp && (grid.cellsX < 2 || grid.cellsY < 2))
    fail("uGIMP needs at least 2 cells in x and y");
  if (!(endTime >= 0.0 && std::isfinite(endTime))) fail("end time must be >= 0 s");
  if (!(outputInterval >= 0.0 && std::isfinite(outputInterval))) fail("output interval must be >= 0 s");
  if (snapshotEvery < 1) fail("snapshot_every must be >= 1");
  if (checkpoint.everySteps < 0) fail("checkpoint every_steps must be >= 1 (0: off)");
  if (!(checkpoint.everyMinutes >= 0.0 && std::isfinite(checkpoint.everyMinutes)))
    fail("checkpoint every_minutes must be > 0 (0: off)");
  for (const auto& c : conditions) {
    if (!(c.box.max[0] >= c.box.min[0] && c.box.max[1] >= c.box.min[1])) fail("condition '" + c.name + "': box needs max >= min");
    for (const auto& k : c.component) checkHistory(k.history, "condition '" + c.name + "'");
    if (c.field) {
      checkHistory(c.field->scale, "condition '" + c.name + "'");
      if (!c.field->gradient.allFinite()) fail("condition '" + c.name + "': velocity gradient must be finite");
    }
  }
  if (stopWhen) {
    if (!findCondition(conditions, stopWhen->condition)) fail("stop_when: no condition is named '" + stopWhen->condition + "'");
    if (!(stopWhen->loadBelow > 0.0 && stopWhen->loadBelow < 1.0)) fail("stop_when: load_below must be in (0, 1)");
    if (!(stopWhen->afterTime >= 0.0 && std::isfinite(stopWhen->afterTime))) fail("stop_when: after_time must be >= 0 s");
    if (!(outputInterval > 0.0)) fail("stop_when is checked at the output rows: needs output_interval > 0");
  }
  for (const auto& l : loads) {
    if (!(l.box.max[0] >= l.box.min[0] && l.box.max[1] >= l.box.min[1])) fail("load '" + l.name + "': box needs max >= min");
    if (!l.force.allFinite()) fail("load '" + l.name + "': force must be finite");
    checkHistory(l.history, "load '" + l.name + "'");
  }
}

}  // namespace ecm::mpm
