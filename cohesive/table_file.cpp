#include "cohesive/table_file.hpp"

#include <fstream>
#include <string>

#include "io/csv_reader.hpp"
#include "io/yaml_input.hpp"

namespace ecm::cohesive {

namespace {

// The line of the header: the first that is neither blank nor a '#' comment (readCsv keeps the
// header's names, not its line).
int headerLine(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    const auto first = line.find_first_not_of(" \t\r");
    if (first != std::string::npos && line[first] != '#') return n;
  }
  return 1;
}

}  // namespace

TableInterface readTableFile(const std::filesystem::path& file) {
  const io::CsvTable csv = io::readCsv(file, 2);
  // The header carries the units: a table in other units must not pass as mm and MPa.
  if (csv.header != std::vector<std::string>{"opening_mm", "traction_MPa"})
    throw io::InputError(file.string(), headerLine(file), "the table's header line must be 'opening_mm,traction_MPa' (units mm and MPa)");
  TableInterface t;
  t.source = file.string();
  for (const std::vector<double>& row : csv.rows) {
    t.opening.push_back(row[0]);
    t.traction.push_back(row[1]);
  }
  try {
    t.checkRows();
  } catch (const TableRowError& e) {
    const int line = e.row < csv.lines.size() ? csv.lines[e.row] : headerLine(file);
    throw io::InputError(file.string(), line, e.what());
  }
  return t;
}

}  // namespace ecm::cohesive
