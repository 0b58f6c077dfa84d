#pragma once
// The error a scene's validate() throws: a value out of range or inconsistent with another,
// named by its key path in the input ("solver.cfl", "materials[1]", "" for the whole scene) so
// that a YAML reader can report it at the line the value came from (YamlMap::failAt).
#include <stdexcept>
#include <string>

namespace ecm::io {

struct ValueError : std::invalid_argument {
  ValueError(std::string keyPath, const std::string& reason)
      : std::invalid_argument(keyPath.empty() ? reason : "key '" + keyPath + "': " + reason),
        key(std::move(keyPath)),
        reason(reason) {}
  std::string key;
  std::string reason;
};

}  // namespace ecm::io
