#pragma once
// Reading small numeric CSV tables (measured curves): comma-separated numbers, lines starting
// with '#' and blank lines ignored, an optional header line of names first. Malformed input is an
// InputError "FILE:LINE: reason".
#include <filesystem>
#include <string>
#include <vector>

namespace ecm::io {

struct CsvTable {
  std::filesystem::path file;
  std::vector<std::string> header;         // empty when the file has none
  std::vector<std::vector<double>> rows;   // all of the same length
  std::vector<int> lines;                  // 1-based file line of each row
};

// Every row must hold exactly `columns` finite numbers (any count, equal for all rows, if 0).
CsvTable readCsv(const std::filesystem::path& path, std::size_t columns = 0);

}  // namespace ecm::io
