// Fuzz harness: a material map in YAML. Only InputError may come out of the reader.
#include <cstdint>
#include <string>

#include "io/material_yaml.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const ecm::MaterialParams p = ecm::io::readMaterial(ecm::io::parseYaml(text, "fuzz.yaml"));
    ecm::Material m(p);  // accepted parameters must build a model
  } catch (const ecm::io::InputError&) {
  }
  return 0;
}
