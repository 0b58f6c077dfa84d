// Fuzz harness: an ecm-mpm scene file. Only InputError (and the material's ParameterError,
// which the reader turns into InputError) may come out of the reader; the run is not started.
#include <cstdint>
#include <string>

#include "mpm/scene/scene_yaml.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    (void)ecm::mpm::readScene(ecm::io::parseYaml(text, "fuzz.yaml"));
  } catch (const ecm::io::InputError&) {
  }
  return 0;
}
