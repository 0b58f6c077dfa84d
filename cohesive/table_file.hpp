#pragma once
// The `table` law's rows from a CSV file: '#' comment lines, the header line
// `opening_mm,traction_MPa`, then one row per line (io::readCsv). Anything wrong with a row is an
// io::InputError at its line ("FILE:LINE: reason"); K0 is the scene's and is checked there.
#include <filesystem>

#include "cohesive/table_interface.hpp"

namespace ecm::cohesive {

TableInterface readTableFile(const std::filesystem::path& file);

}  // namespace ecm::cohesive
