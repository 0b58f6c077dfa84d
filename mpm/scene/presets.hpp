#pragma once
// Speed-versus-accuracy presets of ecm-mpm (scene key `preset: fast | balanced | accurate`),
// chosen from the measured Pareto front of data/studies/den-coarse-presets.yaml (the whole DEN
// 4b scene on the coarse mesh; figures in docs/performance.md, "Presets"). A preset sets the
// discretisation knobs below; a scene that names one may not set them itself (one source for
// each knob). The mesh (cell size) stays the scene's: it is geometry, and H follows it.
#include <span>
#include <string>
#include <string_view>

#include "mpm/scene/scene.hpp"

namespace ecm::mpm {

struct Preset {
  std::string_view name;
  int particlesPerCell;  // k x k per cell
  ShapeFunction shapeFunction;
  UpdateScheme scheme;
  double cfl;
};

std::span<const Preset> presets();
// nullptr if no preset has this name.
const Preset* findPreset(std::string_view name);
// "fast, balanced, accurate": for messages.
std::string presetNames();
// Sets the preset's knobs on a scene and records its name.
void applyPreset(const Preset& p, Scene& scene);

}  // namespace ecm::mpm
