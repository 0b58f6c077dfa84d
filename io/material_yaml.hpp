#pragma once
// Materials in YAML: read an ecm::MaterialParams from a map (inline, or `file: NAME.yaml`) and
// write one back. The format (units: mm, N, MPa, tonne; density in t/mm^3):
//
//   name: den-concrete
//   model: enriched          # enriched | smeared_crack | linear_elastic
//   hypothesis: plane_stress # plane_stress | plane_strain | three_dimensional (3D callers only)
//   youngs_modulus: 32000    # E (MPa)
//   poisson_ratio: 0.2       # nu
//   density: 2.4e-9          # t/mm^3 (optional, 0 = not given)
//   tensile_strength: 3.0    # f_t' (MPa)                  smeared_crack, enriched
//   softening_modulus: 8.184 # E_p (MPa)                   smeared_crack, enriched
//   softening_exponent: 0.128# n                           smeared_crack, enriched
//   band_width: 0.05         # h (mm)                      enriched only
//   fracture_energy: 0.11    # G_F (N/mm), optional: informational, or the regularisation target
//   regularised_for_size: 100# H (mm), smeared_crack only: E_p is then the crack-band value for H
//                            # (needs fracture_energy; softening_modulus must then be left out)
//
// Keys a model does not use are refused (e.g. band_width for linear_elastic). A `file:` reference
// resolves relative to the folder of the referring YAML file, then in DATA_DIR/materials/.
// See data/materials/README.md.
#include <filesystem>
#include <string>

#include "io/yaml_input.hpp"
#include "material/material.hpp"

namespace ecm::io {

// $ECM_DATA_DIR if set, else the project's data/ folder (compile definition ECM_DATA_DIR).
std::filesystem::path defaultDataDir();

// Reads a material map (and checks that it has no unknown keys). Range errors of
// MaterialParams::validate() come back as InputError at the line of the offending key.
MaterialParams readMaterial(const YamlMap& map, const std::filesystem::path& dataDir = defaultDataDir());
// A standalone material file.
MaterialParams loadMaterialFile(const std::filesystem::path& path);

// `snap_back: release | stop` (default release) of a point or MPM scene. The old point-scene key
// `on_snapback: jump | stop` is refused with a message naming the new key and value.
SnapBackPolicy readSnapBackPolicy(const YamlMap& map);

// The file format above, with units comments; numbers in shortest round-trip form.
std::string materialYaml(const MaterialParams& p);
// Validates, then writes atomically (OutputError naming the path on failure).
void writeMaterialFile(const MaterialParams& p, const std::filesystem::path& path);

}  // namespace ecm::io
