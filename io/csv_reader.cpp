#include "io/csv_reader.hpp"

#include <charconv>
#include <cmath>
#include <fstream>

#include "io/yaml_input.hpp"

namespace ecm::io {

namespace {

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos) return {};
  return s.substr(b, s.find_last_not_of(" \t\r") - b + 1);
}

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (true) {
    const auto comma = line.find(',', start);
    out.push_back(trim(line.substr(start, comma == std::string::npos ? std::string::npos : comma - start)));
    if (comma == std::string::npos) return out;
    start = comma + 1;
  }
}

bool parse(const std::string& s, double& v) {
  const char* b = s.data();
  if (!s.empty() && s[0] == '+') ++b;
  const auto [end, ec] = std::from_chars(b, s.data() + s.size(), v);
  return !s.empty() && ec == std::errc() && end == s.data() + s.size();
}

}  // namespace

CsvTable readCsv(const std::filesystem::path& path, std::size_t columns) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw InputError(path.string(), 1, "cannot open file: it does not exist");
  std::ifstream in(path);
  if (!in) throw InputError(path.string(), 1, "cannot open file for reading");
  CsvTable t;
  t.file = path;
  std::string raw;
  int lineNo = 0;
  while (std::getline(in, raw)) {
    ++lineNo;
    const std::string line = trim(raw);
    if (line.empty() || line[0] == '#') continue;
    const std::vector<std::string> cells = split(line);
    std::vector<double> values(cells.size());
    bool numeric = true;
    for (std::size_t i = 0; i < cells.size() && numeric; ++i) numeric = parse(cells[i], values[i]);
    if (!numeric && t.rows.empty() && t.header.empty()) {
      t.header = cells;  // the header line
      if (columns == 0) columns = cells.size();
      if (cells.size() != columns)
        throw InputError(path.string(), lineNo, "expected " + std::to_string(columns) + " columns, the header has " +
                                                    std::to_string(cells.size()));
      continue;
    }
    for (std::size_t i = 0; i < cells.size(); ++i) {
      if (!parse(cells[i], values[i]))
        throw InputError(path.string(), lineNo, "column " + std::to_string(i + 1) + ": '" + cells[i] + "' is not a number");
      if (!std::isfinite(values[i]))
        throw InputError(path.string(), lineNo, "column " + std::to_string(i + 1) + ": '" + cells[i] + "' is not finite");
    }
    if (columns == 0) columns = cells.size();
    if (cells.size() != columns)
      throw InputError(path.string(), lineNo, "expected " + std::to_string(columns) + " numbers, got " +
                                                  std::to_string(cells.size()));
    t.rows.push_back(std::move(values));
    t.lines.push_back(lineNo);
  }
  if (in.bad()) throw InputError(path.string(), lineNo, "read error");
  return t;
}

}  // namespace ecm::io
