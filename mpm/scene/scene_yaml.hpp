#pragma once
// Scenes in YAML (the edge: nothing runs on a half-understood file; every error is FILE:LINE:
// reason). The reader checks the form (keys, types, which keys go together); the values are
// checked by Scene::validate, the one checker, whose errors the reader reports at the line of
// the key they name. Format, with units mm, N, MPa, tonne (t), s; density in t/mm^3:
//
//   name: tension-block
//   grid: {origin: [0, 0], cell_size: [10, 10], cells: [10, 12]}   # mm, mm, count
//   thickness: 1                # mm
//   particles_per_cell: 2       # k: k x k per cell
//   preset: balanced            # optional: fast | balanced | accurate (mpm/scene/presets.hpp) sets
//                               # particles_per_cell and solver shape_function, scheme, cfl,
//                               # which the scene may then not set itself
//   materials:                  # inline maps (io/material_yaml.hpp format) or {file: NAME.yaml}
//     - {file: den-concrete.yaml}
//   bodies:                     # later bodies override earlier ones
//     - {rectangle: {min: [0, 0], max: [100, 100]}, material: den-concrete}
//     - {polygon: [[0, 45], [20, 50], [0, 55]], subtract: true}
//     - {circle: {center: [50, 50], radius: 5}, subtract: true, initial_velocity: [0, 0]}
//     - rve:                    # a mesoscale sample (mpm/scene/rve_sample.hpp): expands into the matrix
//         side: 25              #   square, the ITZ circles (r + t), the inclusion circles (r)
//         origin: [0, 0]        # mm, optional
//         seed: 1               # integer in [0, 2^31)
//         volume_fraction: 0.4  # inclusion area fraction (ITZ not counted), (0, 1)
//         diameters: [1, 4]     # d_min, d_max (mm): Fuller curve P = (d / d_max)^fuller_exponent
//         fuller_exponent: 0.5  #   optional (default 0.5)
//         # or grading: [[d, passing], ...]   increasing (mm, any scale), instead of diameters
//         itz_thickness: 0.1    # t (mm)
//         gap: 0.1              # mm between ITZ rings and to the sides, optional (default 0.1 d_min)
//         attempts: 20000       # trial centres per inclusion, optional
//         tolerance: 0.005      # accepted shortfall of the fraction, optional
//         matrix: rve-matrix    # material names
//         inclusion: rve-inclusion
//         itz: rve-itz
//   solver:                     # all optional
//     scheme: usl               # usf | usl | musl
//     shape_function: linear    # linear | ugimp | bspline2
//     flip: 1.0                 # PIC/FLIP blend (1 = FLIP)
//     cfl: 0.3                  # (0, 1]
//     effective_size: sqrt      # sqrt | oriented (enriched materials)
//     local_damping: 0.0        # Cundall, [0, 1)
//     viscous_damping: 0.0      # 1/s
//     gravity: [0, 0]           # mm/s^2
//     substep_levels: 4         # failed material updates retried with up to 2^levels sub-steps
//     snap_back: release        # release | stop: an enriched point with no stable branch fails
//                               # onto its stable branch (counted in summary.json) or stops the run
//     crack_path: tracked       # tracked | free: where an enriched point may open its band;
//                               # tracked: only on the crack paths the run tracks, with their
//                               # normals and effective sizes (docs/model.md, "Crack paths");
//                               # free (the paper's rule): wherever it reaches onset
//   (or, implicit: solver: {scheme: implicit_static, tolerance: 1e-6, max_iterations: 25,
//    max_halvings: 8, onset_overshoot: 0.05, accept_tolerance: 1e-4, linear_solver: umfpack,  # | sparselu | amg
//    load_step: S | control: {indirect: {driven: [..], reference: [x, y],
//    opening: [{node: [x, y], component: y, coefficient: 1}, ..], step: MM, until: MM, from: S}}};
//    shape_function, effective_size, gravity, substep_levels and snap_back as above; no flip,
//    cfl or damping; the defaults are ImplicitSettings' (mpm/scene/solver_settings.hpp);
//    docs/implicit.md, docs/inputs.md)
//   end_time: 1e-3              # s
//   output_interval: 1e-5       # s (0: first and last step only)
//   snapshot_every: 10          # optional: a VTU snapshot every N-th output step (default 1)
//   particle_snapshots: [2e-4]  # s, increasing, optional: particles_t<time>.csv (x, y, damage,
//                               # material, opening) at the first step at or past each time
//   checkpoint:                 # optional: DIR/checkpoint.bin every N steps and/or M minutes
//     every_steps: 5000         #   of wall time (integer >= 1); at least one of the two keys.
//     every_minutes: 30         #   > 0. A stop (SIGINT, SIGTERM, --max-steps) always writes one;
//                               #   resume with ecm-mpm SCENE.yaml --restart DIR
//   conditions:                 # on the grid nodes inside a box
//     - name: base
//       box: {min: [0, 0], max: [100, 0]}
//       fixed: [x, y]
//     - name: top
//       box: {min: [0, 100], max: [100, 100]}
//       displacement: {y: {type: smooth_ramp, value: 0.05, time: 1e-3}}   # mm
//       velocity: {x: {type: hold, value: 0}}                              # mm/s
//     - name: drive             # or an affine velocity field v = scale(t) G (x - origin)
//       box: {min: [0, 0], max: [100, 100]}
//       velocity_field: {gradient: [[1, 0], [0, 0]], origin: [0, 0], scale: {type: hold, value: 1}}
//   loads:                      # total force spread equally over the set
//     - {name: pull, box: {min: [0, 95], max: [100, 100]}, on: particles, force: [0, 1000],
//        history: {type: linear_ramp, value: 1, time: 1e-4}}
//   platens:                    # optional: rigid loading platens (mpm/scene/platen.hpp)
//     - name: frame
//       boxes: [{min: [0, 200], max: [200, 200]}, {min: [0, 100], max: [0, 195]}]  # its nodes
//       reference: [0, 200]     # mm: its rotation's and moment's point (default: the nodes' mean)
//       x: {force: {type: linear_ramp, value: 10000, time: 1e-3}}        # N on the specimen
//       y: {displacement: {type: linear_ramp, value: 0.1, time: 1e-2}, free_until: 2e-3}   # mm
//       rotation: held          # held | free | {displacement: H} (rad) | {force: H} (N mm)
//   stop_when:                  # optional: end before end_time at the first output row (at or
//     condition: top            #   after after_time) where this condition's reaction along its
//     load_below: 0.1           #   driven component is below load_below (in (0, 1)) times its
//     after_time: 5e-4          #   peak over the rows so far (s, >= 0, < end_time; default 0);
//                               #   needs output_interval > 0
//     (or: stop_when: {gauge: delta, reaches: 0.1}: at the first row where that gauge reads at
//      least 0.1 mm in magnitude)
//   gauges:                     # optional: history.csv columns NAME_mm (mpm/scene/gauge.hpp)
//     - {name: delta, at: [50, 67.5], to: [50, 132.5], component: y}  # u_y(to) - u_y(at), mm
//     - {name: tip, at: [100, 5], component: x}                       # u_x of one material point
//     # each point follows the particle seeded nearest to it (within one particle spacing, else refused);
//     # solver.control.indirect may name a gauge (gauge: delta) instead of opening: [...]
//
// Histories: {type: hold, value: V} | {type: linear_ramp | smooth_ramp, value: V, time: T}
//          | {type: table, points: [[t0, v0], [t1, v1], ...]}
#include <filesystem>

#include "io/yaml_input.hpp"
#include "mpm/scene/rve_sample.hpp"
#include "mpm/scene/scene.hpp"

namespace ecm::mpm {

Scene readScene(const io::YamlMap& map);
Scene loadSceneFile(const std::filesystem::path& path);

// The sample parameters of an `rve:` map (all keys above except the material names). Out-of-range
// values are InputErrors; the sample itself is not generated.
RveParams readRveParams(const io::YamlMap& rve);
// The parameters of every `rve:` body of a scene map, in order (for tools such as ecm-rve).
std::vector<RveParams> sceneRveParams(const io::YamlMap& scene);

}  // namespace ecm::mpm
