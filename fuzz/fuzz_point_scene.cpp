// Fuzz harness: an ecm-point scene. Only InputError may come out of the reader; an accepted
// scene (capped at 300 increments) must run without crashing and give finite numbers.
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "driver/point_scene_yaml.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  ecm::driver::PointScene scene;
  try {
    scene = ecm::driver::readPointScene(ecm::io::parseYaml(text, "fuzz.yaml"));
  } catch (const ecm::io::InputError&) {
    return 0;
  }
  if (ecm::driver::totalIncrements(scene) > 300) return 0;
  const ecm::driver::PointRun run = ecm::driver::runPoint(scene);
  for (const ecm::driver::HistoryRow& r : run.history)
    if (!r.stress.allFinite() || !r.strain.allFinite() || !std::isfinite(r.dissipation) || r.dissipation < -1e-12)
      std::abort();
  return 0;
}
