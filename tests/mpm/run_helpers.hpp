#pragma once
// What the MPM tests that run whole scenes share: quiet run options (one thread, no progress, no
// plots, no VTU) and history.csv read back as rows of name -> value.
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "mpm/run.hpp"

namespace ecm::mpm::test {

inline RunOptions quietRun(const std::filesystem::path& dir) {
  RunOptions o;
  o.outputDir = dir;
  o.threads = 1;
  o.progress = false;
  o.plot = false;
  o.snapshots = false;
  return o;
}

// Every row of a history.csv, as column name -> value.
inline std::vector<std::map<std::string, double>> historyRows(const std::filesystem::path& csv) {
  std::ifstream in(csv);
  std::string header, line;
  std::getline(in, header);
  std::vector<std::string> names;
  std::stringstream h(header);
  for (std::string n; std::getline(h, n, ',');) names.push_back(n);
  std::vector<std::map<std::string, double>> out;
  while (std::getline(in, line)) {
    std::stringstream v(line);
    std::map<std::string, double> row;
    std::string value;
    for (const std::string& n : names)
      if (std::getline(v, value, ',')) row[n] = std::stod(value);
    out.push_back(std::move(row));
  }
  return out;
}

// The last row of a history.csv.
inline std::map<std::string, double> lastRow(const std::filesystem::path& csv) {
  const auto rows = historyRows(csv);
  return rows.empty() ? std::map<std::string, double>{} : rows.back();
}

}  // namespace ecm::mpm::test
