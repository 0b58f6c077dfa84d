#pragma once
// The plain description of an MPM run: grid, materials, bodies, boundary conditions, loads and
// solver settings. Built in C++ (tests) or by the YAML reader (mpm/scene/scene_yaml.hpp); checked
// once by validate(), the one checker of a scene's values; the solver trusts a validated scene.
#include <optional>
#include <string>
#include <vector>

#include "material/material.hpp"
#include "mpm/scene/boundary.hpp"
#include "mpm/scene/gauge.hpp"
#include "mpm/scene/platen.hpp"
#include "mpm/scene/geometry.hpp"
#include "mpm/core/grid.hpp"
#include "mpm/core/shape_function.hpp"
#include "mpm/scene/solver_settings.hpp"
#include "mpm/scene/stop_when.hpp"

namespace ecm::mpm {

// When a run writes its checkpoint (mpm/explicit/explicit_checkpoint.hpp) besides on a stop request: every N steps
// and/or every M minutes of wall time (0: never).
struct CheckpointSettings {
  long everySteps = 0;
  double everyMinutes = 0.0;
};

struct Scene {
  std::string name = "scene";
  std::string preset;       // the preset that set the discretisation knobs (mpm/scene/presets.hpp), or empty
  Grid grid;
  double thickness = 1.0;  // mm (plane stress: the plate; plane strain: the slice)
  std::vector<MaterialParams> materials;
  std::vector<Body> bodies;
  int particlesPerCell = 2;  // k: k x k particles per cell
  std::vector<NodeCondition> conditions;
  std::vector<Load> loads;
  std::vector<Platen> platens;  // rigid loading platens (mpm/scene/platen.hpp)
  std::vector<Gauge> gauges;  // history.csv columns <name>_mm (mpm/scene/gauge.hpp)
  SolverSettings solver;
  double endTime = 0.0;         // s: the latest end
  std::optional<StopWhen> stopWhen;  // an earlier end by a condition's load (mpm/scene/stop_when.hpp)
  double outputInterval = 0.0;  // s between output steps (0: only the first and last)
  int snapshotEvery = 1;        // a VTU snapshot at every N-th output step (and the last)
  std::vector<double> particleSnapshots;  // s, increasing: particles_t<time>.csv at each (maps of states)
  CheckpointSettings checkpoint;

  // Throws io::ValueError naming the key path of the value that is wrong ("solver.cfl",
  // "materials[1]"), so that the YAML reader can give its line.
  void validate() const;
};

}  // namespace ecm::mpm
