#include "io/material_yaml.hpp"

#include <charconv>
#include <cstdlib>
#include <sstream>

#include "io/atomic_file.hpp"
#include "material/parameter_check.hpp"

#ifndef ECM_DATA_DIR
#define ECM_DATA_DIR "data"
#endif

namespace ecm::io {

std::filesystem::path defaultDataDir() {
  if (const char* env = std::getenv("ECM_DATA_DIR"); env && *env) return env;
  return ECM_DATA_DIR;
}

namespace {

ModelKind modelKind(const std::string& s) {
  if (s == "linear_elastic") return ModelKind::LinearElastic;
  if (s == "smeared_crack") return ModelKind::SmearedCrack;
  return ModelKind::Enriched;
}

// A key needed by some models only: required for them, refused for the others.
double modelKey(const YamlMap& m, const std::string& key, bool needed, const std::string& model) {
  if (!needed) {
    m.reject(key, "is not used by model " + model);
    return 0.0;
  }
  return m.get<double>(key);
}

std::filesystem::path resolve(const YamlMap& map, const std::filesystem::path& dataDir) {
  const std::filesystem::path ref = map.get<std::string>("file");
  std::vector<std::filesystem::path> candidates;
  if (ref.is_absolute()) {
    candidates.push_back(ref);
  } else {
    candidates.push_back(map.directory() / ref);
    candidates.push_back(dataDir / "materials" / ref);
  }
  std::string looked;
  for (const auto& c : candidates) {
    std::error_code ec;
    if (std::filesystem::is_regular_file(c, ec)) return c;
    looked += (looked.empty() ? "" : ", ") + c.string();
  }
  map.fail("file", "material file '" + ref.string() + "' not found (looked in: " + looked + ")");
}

MaterialParams readInline(const YamlMap& m, const std::string& defaultName) {
  MaterialParams p;
  p.name = m.getOr<std::string>("name", defaultName);
  const std::string model = m.getEnum("model", {"enriched", "smeared_crack", "linear_elastic"});
  p.model = modelKind(model);
  const std::string hypothesis = m.getEnum("hypothesis", {"plane_stress", "plane_strain", "three_dimensional"});
  p.elastic.hypothesis = hypothesis == "plane_strain"        ? Hypothesis::PlaneStrain
                         : hypothesis == "three_dimensional" ? Hypothesis::ThreeDimensional
                                                             : Hypothesis::PlaneStress;
  p.elastic.youngsModulus = m.get<double>("youngs_modulus");
  p.elastic.poissonRatio = m.get<double>("poisson_ratio");
  p.density = m.getOr<double>("density", 0.0);

  const bool cracking = p.model != ModelKind::LinearElastic;
  const bool smeared = p.model == ModelKind::SmearedCrack;
  const bool regularised = smeared && m.has("regularised_for_size");
  p.tensileStrength = modelKey(m, "tensile_strength", cracking, model);
  p.softeningExponent = modelKey(m, "softening_exponent", cracking, model);
  if (regularised) {
    m.reject("softening_modulus", "is replaced by the crack-band value when regularised_for_size is given");
    p.regularisedForSize = m.get<double>("regularised_for_size", Range::positive());
    p.fractureEnergy = m.get<double>("fracture_energy", Range::positive());
  } else {
    p.softeningModulus = modelKey(m, "softening_modulus", cracking, model);
    if (!smeared) m.reject("regularised_for_size", "is used by model smeared_crack only");
    if (cracking) {
      p.fractureEnergy = m.getOr<double>("fracture_energy", 0.0, Range::positive());
    } else {
      m.reject("fracture_energy", "is not used by model " + model);
    }
  }
  p.bandWidth = modelKey(m, "band_width", p.model == ModelKind::Enriched, model);
  if (p.model == ModelKind::Enriched) {
    p.secondBand = m.getEnumOr("second_band", std::array{SecondBandOption::Off, SecondBandOption::Orthogonal}, p.secondBand);
  } else {
    m.reject("second_band", "is used by model enriched only (model " + model + " has no band)");
  }
  m.finish();
  try {
    p.validate();
  } catch (const ParameterError& e) {
    // At the line of the key at fault (line(key) falls back to the map's line).
    throw InputError(m.file(), e.key.empty() ? m.line() : m.line(e.key), "material '" + p.name + "': " + e.what());
  }
  return p;
}

}  // namespace

MaterialParams readMaterial(const YamlMap& map, const std::filesystem::path& dataDir) {
  if (map.has("file")) {
    const std::filesystem::path path = resolve(map, dataDir);
    map.finish();  // `file:` stands alone
    return loadMaterialFile(path);
  }
  return readInline(map, map.path().empty() ? "material" : map.path());
}

SnapBackPolicy readSnapBackPolicy(const YamlMap& map) {
  map.reject("on_snapback", "renamed: write snap_back: release (was jump) or snap_back: stop");
  return map.getEnumOr("snap_back", std::array{SnapBackPolicy::Release, SnapBackPolicy::Stop}, kDefaultSnapBack);
}

MaterialParams loadMaterialFile(const std::filesystem::path& path) {
  const YamlMap m = loadYamlFile(path);
  m.reject("file", "a material file cannot refer to another material file");
  return readInline(m, path.stem().string());
}

namespace {
std::string num(double v) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

std::string quotedName(const std::string& name) {
  YAML::Emitter e;
  e << name;
  return e.c_str();
}

void line(std::ostringstream& out, const std::string& key, const std::string& value, const std::string& comment) {
  std::string k = key + ": " + value;
  if (k.size() < 26) k.resize(26, ' ');
  out << k << " # " << comment << '\n';
}

void line(std::ostringstream& out, const std::string& key, double v, const std::string& comment) {
  line(out, key, num(v), comment);
}
}  // namespace

std::string materialYaml(const MaterialParams& p) {
  std::ostringstream out;
  out << "# ecm material. Units: mm, N, MPa, tonne (density in t/mm^3).\n";
  out << "name: " << quotedName(p.name) << '\n';
  line(out, "model", toString(p.model), "enriched | smeared_crack | linear_elastic");
  line(out, "hypothesis", toString(p.elastic.hypothesis), "plane_stress | plane_strain | three_dimensional");
  line(out, "youngs_modulus", p.elastic.youngsModulus, "E (MPa)");
  line(out, "poisson_ratio", p.elastic.poissonRatio, "nu (-)");
  if (p.density > 0.0) line(out, "density", p.density, "t/mm^3");
  if (p.model == ModelKind::LinearElastic) return out.str();
  line(out, "tensile_strength", p.tensileStrength, "f_t' (MPa)");
  const bool regularised = p.model == ModelKind::SmearedCrack && p.regularisedForSize > 0.0;
  if (!regularised) line(out, "softening_modulus", p.softeningModulus, "E_p (MPa)");
  line(out, "softening_exponent", p.softeningExponent, "n (-)");
  if (p.model == ModelKind::Enriched) line(out, "band_width", p.bandWidth, "h (mm)");
  if (p.secondBand != SecondBandOption::Off) line(out, "second_band", toString(p.secondBand), "off | orthogonal");
  if (p.fractureEnergy > 0.0) line(out, "fracture_energy", p.fractureEnergy, "G_F (N/mm)");
  if (regularised) line(out, "regularised_for_size", p.regularisedForSize, "H (mm): E_p from G_F/H (crack band)");
  return out.str();
}

void writeMaterialFile(const MaterialParams& p, const std::filesystem::path& path) {
  p.validate();
  writeFileAtomically(path, materialYaml(p));
}

}  // namespace ecm::io
