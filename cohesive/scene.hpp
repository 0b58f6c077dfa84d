#pragma once
// A cohesive reference scene: the problem, its mesh size, the interface law and the control.
// Read from YAML at the edge (scene.cpp); everything past it works on this validated struct.
#include <filesystem>
#include <optional>
#include <string>

#include "cohesive/interface_law.hpp"
#include "cohesive/model.hpp"
#include "cohesive/solver.hpp"

namespace ecm::cohesive {

enum class Problem { beam, denTension, bar };

struct Scene {
  std::string name;
  std::string file;  // where it was read from
  Problem problem = Problem::beam;
  ElasticBulk bulk;
  double fractureEnergy = 0.0;  // G_F (N/mm)
  double cellSize = 1.25;       // target cell size (mm)
  InterfaceLaw law;
  BeamGeometry beam;
  PanelGeometry panel;
  BarGeometry bar;
  SolverSettings solver;
};

// What the command line may change (ecm-cohesive --cell, --law).
struct SceneOverrides {
  std::optional<double> cellSize;
  std::optional<LawKind> law;
};

// Throws io::InputError "FILE:LINE: reason" on an unknown, missing or wrong key or value.
Scene readScene(const std::filesystem::path& path, const SceneOverrides& overrides = {});
Scene parseScene(const std::string& text, const std::string& name, const SceneOverrides& overrides = {});

HalfModel buildModel(const Scene& scene);

}  // namespace ecm::cohesive
