#include "mpm/scene/presets.hpp"

#include <stdexcept>

#include <array>

namespace ecm::mpm {

namespace {

// Measured on the DEN 4b coarse scene, whole run (data/studies/den-coarse-presets.yaml), errors
// against 3 x 3 particles per cell at CFL 0.25, CPU time of one thread (docs/performance.md,
// "Presets"):
//   fast      1 x 1, CFL 0.5    peak +0.3 %, dissipated energy +3.7 %,   9.6 s
//   balanced  2 x 2, CFL 0.5    peak -0.2 %, dissipated energy -0.4 %,  33 s
//   accurate  2 x 2, CFL 0.25   peak -0.04 %, dissipated energy +0.13 %, 68 s
// (3 x 3 at CFL 0.5: 0.18 % for 75 s, dominated; CFL 0.7 was unstable with every sampling:
// the 2D limit of bilinear cells with lumped mass is 1/sqrt(2)). Linear shape functions, USL.
constexpr std::array<Preset, 3> kPresets{{
    {"fast", 1, ShapeFunction::Linear, UpdateScheme::USL, 0.5},
    {"balanced", 2, ShapeFunction::Linear, UpdateScheme::USL, 0.5},
    {"accurate", 2, ShapeFunction::Linear, UpdateScheme::USL, 0.25},
}};

}  // namespace

std::span<const Preset> presets() { return kPresets; }

const Preset* findPreset(std::string_view name) {
  for (const Preset& p : kPresets)
    if (p.name == name) return &p;
  return nullptr;
}

std::string presetNames() {
  std::string names;
  for (const Preset& p : kPresets) names += (names.empty() ? "" : ", ") + std::string(p.name);
  return names;
}

void applyPreset(const Preset& p, Scene& scene) {
  if (scene.solver.implicit)
    throw std::invalid_argument("the presets set explicit knobs (time step, scheme); scene '" + scene.name +
                                "' is implicit_static");
  scene.preset = std::string(p.name);
  scene.particlesPerCell = p.particlesPerCell;
  scene.solver.shapeFunction = p.shapeFunction;
  scene.solver.explicitScheme.scheme = p.scheme;
  scene.solver.explicitScheme.cfl = p.cfl;
}

}  // namespace ecm::mpm
