#pragma once
// What a point run leaves in its output folder: history.csv (every increment), summary.json
// and the plots stress_strain.png and traction_opening.png.
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "driver/point_driver.hpp"
#include "io/gnuplot.hpp"

namespace ecm::driver {

// The columns of history.csv and one row of numbers per history row (what the CSV holds, and
// what the Python module returns as arrays).
struct HistoryTable {
  std::vector<std::string> columns;
  std::vector<std::vector<double>> rows;
};
HistoryTable historyTable(const PointRun& run, bool secondBandColumns = false);
void writeHistoryCsv(const PointRun& run, const std::filesystem::path& file, bool secondBandColumns = false);
nlohmann::json pointSummaryJson(const PointScene& scene, const PointRun& run);
// The two plots of a point run (stress_strain.png, traction_opening.png): each stress against its
// own strain, markers only for the kinds of event rows the run has, and the second band's
// traction against its jump once it has opened.
std::vector<io::PlotSpec> pointPlotSpecs(const PointScene& scene, const PointRun& run);
void writePointPlots(const PointScene& scene, const PointRun& run, const std::filesystem::path& dir);
// All of the above into `dir`.
void writePointOutputs(const PointScene& scene, const PointRun& run, const std::filesystem::path& dir);

// Traction normal to the crack, n . sigma . n (MPa); sigma_xx before cracking.
double normalTraction(const HistoryRow& r);

}  // namespace ecm::driver
