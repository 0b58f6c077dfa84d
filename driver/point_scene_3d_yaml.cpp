// The 3D point scene (driver/point_driver_3d.hpp): the 2D scene's format with six components
// per segment and the 3D presets. Units: mm, N, MPa.
#include <array>

#include "driver/point_driver_3d.hpp"
#include "driver/segment_components_yaml.hpp"
#include "io/material_yaml.hpp"
#include "io/value_error.hpp"

namespace ecm::driver {

namespace {

using io::Range;
using io::YamlMap;

constexpr std::array<const char*, 6> kStrainKeys = {"eps_xx", "eps_yy", "eps_zz", "gamma_yz", "gamma_xz", "gamma_xy"};
constexpr std::array<const char*, 6> kStressKeys = {"sig_xx", "sig_yy", "sig_zz", "sig_yz", "sig_xz", "sig_xy"};

Segment3 readSegment3(const YamlMap& m) {
  Segment3 s;
  s.increments = m.get<int>("increments", Range{1.0, 1e9, true, true});
  readSegmentComponents(m, kStrainKeys, kStressKeys, s.control, s.target);
  return s;
}

}  // namespace

std::vector<Segment3> readPath3(const YamlMap& path) {
  if (path.has("segments")) {
    std::vector<Segment3> segments;
    for (const YamlMap& m : path.sequence("segments")) segments.push_back(readSegment3(m));
    if (segments.empty()) path.fail("segments", "the path has no segments");
    return segments;
  }
  const std::string name = path.getEnum("preset", {"uniaxial_tension", "triaxial", "rotated_axis"});
  const int increments = path.get<int>("increments", Range{1.0, 1e9, true, true});
  const double strain = path.get<double>("strain", Range::positive());
  const double confinement = name == "triaxial" ? path.get<double>("confinement", Range::any()) : 0.0;
  Vec3 direction = Vec3::UnitX();
  if (name == "rotated_axis") {
    const std::vector<double> d = path.getVector("direction", 3, Range::any());
    direction = Vec3(d[0], d[1], d[2]);
    if (!(direction.norm() > 0.0)) path.fail("direction", "the direction must not be zero");
  }
  return presetSegments3(name, strain, increments, confinement, direction);
}

bool isThreeDimensionalScene(const YamlMap& map) {
  if (map.has("hypothesis")) return map.getEnum("hypothesis", {"plane_stress", "plane_strain", "three_dimensional"}) == "three_dimensional";
  return io::readMaterial(map.child("material")).elastic.hypothesis == Hypothesis::ThreeDimensional;
}

PointScene3 readPointScene3(const YamlMap& map) {
  PointScene3 s;
  s.name = map.getOr<std::string>("name", map.file());
  s.material = io::readMaterial(map.child("material"));
  if (map.has("hypothesis")) map.getEnum("hypothesis", {"plane_stress", "plane_strain", "three_dimensional"});
  s.material.elastic.hypothesis = Hypothesis::ThreeDimensional;
  s.effectiveSize = map.get<double>("effective_size", Range::positive());
  s.snapBack = io::readSnapBackPolicy(map);
  s.relativeTolerance = map.getOr<double>("tolerance", s.relativeTolerance, Range::positive());
  s.substepLevels = map.getOr<int>("substep_levels", s.substepLevels, Range{0.0, 20.0, true, true});
  s.path = readPath3(map.child("path"));
  map.finish();
  if (s.material.model == ModelKind::Enriched) {
    if (const std::string why = effectiveSizeProblem(s.effectiveSize, s.material.bandWidth); !why.empty())
      map.fail("effective_size", why);
  }
  try {
    const Material3D check(s.material);
  } catch (const ParameterError& e) {
    map.fail("material", e.what());
  }
  return s;
}

PointScene3 loadPointScene3(const std::filesystem::path& file) { return readPointScene3(io::loadYamlFile(file)); }

}  // namespace ecm::driver
