#include "mpm/scene/unmeasured.hpp"

#include <algorithm>

namespace ecm::mpm {

std::vector<std::string> unmeasuredCombinations(const Scene& scene) {
  std::vector<std::string> notes;
  const bool enriched = std::any_of(scene.materials.begin(), scene.materials.end(),
                                    [](const MaterialParams& m) { return m.model == ModelKind::Enriched; });
  // A tracked band is laid in a point's cell; with wider shape functions a point's strain spans
  // more than its cell, and tracking was measured with linear ones only.
  if (enriched && scene.solver.crackPath == CrackPathRule::Tracked && scene.solver.shapeFunction != ShapeFunction::Linear)
    notes.push_back(std::string("crack_path: tracked with shape_function: ") + toString(scene.solver.shapeFunction) +
                    " is not measured (a point's strain spans more than its cell there; the tracked band was "
                    "measured with linear shape functions)");
  return notes;
}

}  // namespace ecm::mpm
