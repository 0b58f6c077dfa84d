#include "calibration/target_csv.hpp"

#include <sstream>
#include <string>

#include "io/csv_reader.hpp"
#include "io/yaml_input.hpp"
#include "material/parameter_check.hpp"

namespace ecm::calibration {

namespace {
constexpr std::size_t kMinimumPoints = 3;  // as validateTarget asks
}  // namespace

TargetCurve readTargetCsv(const std::filesystem::path& path) {
  const io::CsvTable table = io::readCsv(path, 2);
  const std::string file = path.string();
  TargetCurve t;
  t.source = file;
  for (std::size_t i = 0; i < table.rows.size(); ++i) {
    const double w = table.rows[i][0], sigma = table.rows[i][1];
    if (w < 0.0) throw io::InputError(file, table.lines[i], "opening w = " + numberText(w, 12) + " mm is negative (must be >= 0)");
    if (i > 0 && !(w > t.opening.back()))
      throw io::InputError(file, table.lines[i], "openings must increase strictly: w = " + numberText(w, 12) + " mm after w = " +
                                                     numberText(t.opening.back(), 12) + " mm");
    t.opening.push_back(w);
    t.stress.push_back(sigma);
  }
  if (t.opening.size() < kMinimumPoints)
    throw io::InputError(file, table.lines.empty() ? 1 : table.lines.back(),
                         std::to_string(t.opening.size()) + " data point(s) (w, sigma); at least " +
                             std::to_string(kMinimumPoints) + " are needed");
  return t;
}

}  // namespace ecm::calibration
