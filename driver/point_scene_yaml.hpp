#pragma once
// ecm-point scene files: the YAML edge of the point driver. Everything is validated here
// (file, line, reason); past this point the driver works on a plain PointScene.
#include <filesystem>

#include "driver/point_driver.hpp"
#include "io/yaml_input.hpp"

namespace ecm::driver {

PointScene loadPointScene(const std::filesystem::path& file);
PointScene readPointScene(const io::YamlMap& map);

}  // namespace ecm::driver
