// The UMAT scene (driver/umat_driver.hpp): a `umat:` block instead of `material:`, the 3D
// point's path. Units: mm, N, MPa (PROPS in the UMAT's own units, which must be these).
#include <cmath>

#include "driver/umat_driver.hpp"

namespace ecm::driver {

using io::Range;

bool isUmatScene(const io::YamlMap& map) { return map.has("umat"); }

UmatScene readUmatScene(const io::YamlMap& map) {
  UmatScene s;
  s.name = map.getOr<std::string>("name", map.file());
  if (map.has("hypothesis") && map.getEnum("hypothesis", {"plane_stress", "plane_strain", "three_dimensional"}) != "three_dimensional")
    map.fail("hypothesis", "a UMAT is driven in 3D (NTENS = 6): three_dimensional or leave it out");
  map.reject("material", "a scene drives either ecm's material (material:) or a UMAT (umat:), not both");
  map.reject("effective_size", "a UMAT takes its sizes from PROPS or CELENT (umat.celent)");
  const io::YamlMap u = map.child("umat");
  s.props = u.scalarSequence<double>("props");
  for (std::size_t i = 0; i < s.props.size(); ++i)
    if (!std::isfinite(s.props[i])) u.fail("props", "PROPS(" + std::to_string(i + 1) + ") is not a number");
  const int nstatv = u.get<int>("nstatv", Range{0.0, 100000.0, true, true});
  if (u.has("statev")) {
    s.initialState = u.scalarSequence<double>("statev");
    if (static_cast<int>(s.initialState.size()) != nstatv)
      u.fail("statev", "gives " + std::to_string(s.initialState.size()) + " values for nstatv = " + std::to_string(nstatv));
  } else {
    s.initialState.assign(static_cast<std::size_t>(nstatv), 0.0);
  }
  s.characteristicLength = u.getOr<double>("celent", 0.0, Range::nonNegative());
  s.materialName = u.getOr<std::string>("material_name", s.materialName);
  if (s.materialName.empty() || s.materialName.size() > 80) u.fail("material_name", "CMNAME has 1 to 80 characters");
  s.stressTolerance = map.getOr<double>("stress_tolerance", s.stressTolerance, Range::positive());
  s.substepLevels = map.getOr<int>("substep_levels", s.substepLevels, Range{0.0, 20.0, true, true});
  s.path = readPath3(map.child("path"));
  map.finish();
  return s;
}

}  // namespace ecm::driver
