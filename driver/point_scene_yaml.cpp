#include "driver/point_scene_yaml.hpp"

#include <array>

#include "driver/segment_components_yaml.hpp"
#include "io/material_yaml.hpp"
#include "io/value_error.hpp"

namespace ecm::driver {

namespace {

using io::Range;
using io::YamlMap;

constexpr std::array<const char*, 3> kStrainKeys = {"eps_xx", "eps_yy", "gamma_xy"};
constexpr std::array<const char*, 3> kStressKeys = {"sig_xx", "sig_yy", "sig_xy"};

// One segment: each component given exactly once, as a strain or as a stress.
Segment readSegment(const YamlMap& m) {
  Segment s;
  s.increments = m.get<int>("increments", Range{1.0, 1e9, true, true});
  readSegmentComponents(m, kStrainKeys, kStressKeys, s.control, s.target);
  if (m.has("opening")) {
    s.openingControl = true;
    s.openingTarget = m.get<double>("opening", Range::positive());
    s.firstOpeningIncrement = m.getOr<double>("first_increment", 0.0, Range::nonNegative());
    if (!s.hasStressControl() && s.target.isZero()) m.failHere("an opening-controlled segment needs a strain direction");
    bool anyStrain = false;
    for (int c = 0; c < 3; ++c) anyStrain = anyStrain || (s.control[c] == Control::Strain && s.target[c] != 0.0);
    if (!anyStrain)
      m.failHere("an opening-controlled segment needs at least one non-zero strain component (its direction)");
  }
  return s;
}

std::vector<Segment> readPath(const YamlMap& path, double nu) {
  if (path.has("segments")) {
    std::vector<Segment> segments;
    for (const YamlMap& m : path.sequence("segments")) segments.push_back(readSegment(m));
    if (segments.empty()) path.fail("segments", "the path has no segments");
    return segments;
  }
  PresetPath p;
  p.name = path.getEnum("preset", {"uniaxial_tension", "uniaxial_strain", "biaxial", "pure_shear",
                                   "tension_then_shear", "rotating_principal_axes", "cyclic", "compression"});
  p.increments = path.get<int>("increments", Range{1.0, 1e9, true, true});
  if (p.name == "cyclic") {
    p.cycleStrains = path.getVector("cycle_strains", 0, Range::positive());
  } else {
    p.strain = path.get<double>("strain", Range::positive());
  }
  if (p.name == "biaxial") p.ratio = path.get<double>("ratio", Range::any());
  if (p.name == "tension_then_shear") p.shear = path.get<double>("shear", Range::any());
  if (p.name == "rotating_principal_axes") p.angle = path.get<double>("angle", Range::positive());
  p.opening = path.getOr<double>("opening", 0.0, Range::nonNegative());
  if (p.opening > 0.0) p.firstOpeningIncrement = path.getOr<double>("first_opening_increment", 0.0, Range::nonNegative());
  return presetSegments(p, nu);
}

}  // namespace

PointScene readPointScene(const YamlMap& map) {
  PointScene s;
  s.name = map.getOr<std::string>("name", map.file());
  s.material = io::readMaterial(map.child("material"));
  if (map.has("hypothesis"))
    s.material.elastic.hypothesis =
        map.getEnum("hypothesis", {"plane_stress", "plane_strain"}) == "plane_stress" ? Hypothesis::PlaneStress
                                                                                       : Hypothesis::PlaneStrain;
  s.effectiveSize = map.get<double>("effective_size");
  s.snapBack = io::readSnapBackPolicy(map);
  s.relativeTolerance = map.getOr<double>("tolerance", s.relativeTolerance);
  s.substepLevels = map.getOr<int>("substep_levels", s.substepLevels);
  s.path = readPath(map.child("path"), s.material.elastic.poissonRatio);
  map.finish();
  try {
    s.validate();  // the values, checked in one place (PointScene::validate)
  } catch (const io::ValueError& e) {
    map.failAt(e.key, e.reason);
  }
  return s;
}

PointScene loadPointScene(const std::filesystem::path& file) { return readPointScene(io::loadYamlFile(file)); }

}  // namespace ecm::driver
