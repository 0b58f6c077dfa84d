#include "driver/point_output.hpp"

#include <sstream>
#include <string>
#include <vector>

#include "io/csv_writer.hpp"
#include "io/gnuplot.hpp"
#include "io/json_summary.hpp"

namespace ecm::driver {

double normalTraction(const HistoryRow& r) {
  if (!r.crackNormal.any()) return r.stress[0];
  const Vec2& n = r.crackNormal;
  return n[0] * n[0] * r.stress[0] + n[1] * n[1] * r.stress[1] + 2.0 * n[0] * n[1] * r.stress[2];
}

HistoryTable historyTable(const PointRun& run, bool secondBandColumns) {
  HistoryTable t;
  t.columns = {"increment", "segment", "eps_xx", "eps_yy", "gamma_xy", "sig_xx", "sig_yy", "sig_xy",
               "damage", "integrity", "jump_n", "jump_t", "opening", "traction_n", "normal_x", "normal_y",
               "volume_fraction", "work", "dissipation", "iterations", "substeps", "opening_control",
               "snapback_release", "event"};
  // With second_band: orthogonal, the second band (zeros until it opens).
  if (secondBandColumns)
    for (const char* c : {"damage_2", "jump_n_2", "jump_t_2", "normal_x_2", "normal_y_2"}) t.columns.emplace_back(c);
  t.rows.reserve(run.history.size());
  for (const HistoryRow& r : run.history) {
    std::vector<double> row{double(r.increment), double(r.segment), r.strain[0], r.strain[1], r.strain[2], r.stress[0],
                            r.stress[1], r.stress[2], r.damage, r.integrity, r.normalJump, r.slidingJump, r.opening,
                            normalTraction(r), r.crackNormal[0], r.crackNormal[1], r.volumeFraction, r.work,
                            r.dissipation, double(r.iterations), double(r.substeps), r.openingControl ? 1.0 : 0.0,
                            r.snapBackRelease ? 1.0 : 0.0, double(r.event)};
    if (secondBandColumns)
      row.insert(row.end(), {r.secondDamage, r.secondNormalJump, r.secondSlidingJump, r.secondNormal[0], r.secondNormal[1]});
    t.rows.push_back(std::move(row));
  }
  return t;
}

void writeHistoryCsv(const PointRun& run, const std::filesystem::path& file, bool secondBandColumns) {
  const HistoryTable t = historyTable(run, secondBandColumns);
  io::CsvWriter csv(file, t.columns);
  for (const std::vector<double>& row : t.rows) csv.row(row);
  csv.close();
}

nlohmann::json pointSummaryJson(const PointScene& scene, const PointRun& run) {
  const PointSummary s = summarise(scene, run);
  nlohmann::json j;
  j["units"] = "mm, N, MPa; energies per unit volume in MPa (N mm/mm^3), H x energy in N/mm";
  j["scene"] = scene.name;
  j["model"] = toString(scene.material.model);
  j["material"] = scene.material.name;
  j["H"] = scene.effectiveSize;
  if (s.onsetStress > 0.0) j["onset_stress"] = s.onsetStress;
  j["peak_stress"] = s.peakStress;
  j["strain_at_peak"] = s.strainAtPeak;
  j["dissipated_energy_per_volume"] = s.dissipation;
  j["H_times_dissipated_energy"] = s.energyPerArea;
  if (scene.material.fractureEnergy > 0.0) {
    j["fracture_energy"] = scene.material.fractureEnergy;
    j["energy_ratio"] = s.energyPerArea / scene.material.fractureEnergy;
  }
  j["work_per_volume"] = s.finalWork;
  j["increments"] = run.history.empty() ? 0 : run.history.back().increment;
  j["completed"] = run.completed;
  if (!run.completed) j["failure"] = run.failure;
  j["snapback_detected"] = run.snapBack.detected;
  if (run.snapBack.detected) {
    j["snapback"] = {{"first_increment", run.snapBack.increment},
                     {"stress_before", run.snapBack.stressBefore},
                     {"jumped", run.snapBack.jumped}};
    if (run.snapBack.jumped) {
      j["snapback"]["stress_after"] = run.snapBack.stressAfter;
      j["snapback"]["stress_drop"] = run.snapBack.stressBefore - run.snapBack.stressAfter;
    }
  }
  if (!run.history.empty()) {
    const HistoryRow& last = run.history.back();
    j["final"] = {{"damage", last.damage}, {"integrity", last.integrity}, {"jump_n", last.normalJump},
                  {"opening", last.opening}, {"normal", {last.crackNormal[0], last.crackNormal[1]}}};
    if (scene.material.secondBand != SecondBandOption::Off) {
      j["second_band"] = toString(scene.material.secondBand);
      j["two_bands"] = last.secondBand ? 1 : 0;  // points with two bands: this point's
      if (last.secondBand) {
        int opened = 0;
        while (!run.history[static_cast<std::size_t>(opened)].secondBand) ++opened;
        j["final"]["second_band"] = {{"damage", last.secondDamage},
                                     {"jump_n", last.secondNormalJump},
                                     {"normal", {last.secondNormal[0], last.secondNormal[1]}},
                                     {"first_row", run.history[static_cast<std::size_t>(opened)].increment}};
      }
    }
  }
  return j;
}

namespace {

// A number as a person writes it: 10, 2.5, 0.001 (not 10.000000).
std::string shortNumber(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

// gnuplot `using` parts of history.csv's columns (1-based, historyTable's order).
constexpr const char* kEvent = "int($24)";
// The row's dominant normal stress and its strain: sig_yy against eps_yy where |sig_yy| > |sig_xx|.
constexpr const char* kDominantStrain = "(abs($7) > abs($6) ? $4 : $3)";
constexpr const char* kDominantStress = "(abs($7) > abs($6) ? $7 : $6)";

}  // namespace

std::vector<io::PlotSpec> pointPlotSpecs(const PointScene& scene, const PointRun& run) {
  unsigned events = 0;
  bool secondBand = false;
  Voigt largest = Voigt::Zero();
  for (const HistoryRow& r : run.history) {
    events |= r.event;
    secondBand = secondBand || r.secondBand;
    largest = largest.cwiseMax(r.stress.cwiseAbs());
  }
  const auto marker = [&](unsigned bit, const std::string& x, const std::string& y, const char* title, const char* style) {
    std::string using_(1, '(');  // (built by appending: GCC 12 warns falsely, -Wrestrict, on "(" + s)
    using_ += kEvent;
    for (const std::string& part : {std::string(" & "), std::to_string(bit), std::string(" ? "), x, std::string(" : 1/0):"), y})
      using_ += part;
    return io::PlotSeries{"history.csv", using_, "", title, style};
  };
  // Each stress against its own strain (a path that holds eps_xx while it stretches eps_yy
  // shows its sig_yy against eps_yy), the components that are never loaded left out.
  io::PlotSpec ss;
  ss.title = scene.name + ": stress-strain (H = " + shortNumber(scene.effectiveSize) + " mm)";
  ss.xLabel = "strain: each stress against its own (eps_xx, eps_yy, gamma_xy)";
  ss.yLabel = "stress (MPa)";
  const double loaded = 1e-6 * largest.maxCoeff();
  const char* names[3] = {"sig_xx against eps_xx", "sig_yy against eps_yy", "sig_xy against gamma_xy"};
  for (int c = 0; c < 3; ++c)
    if (c == 0 || largest[c] > loaded)
      ss.series.push_back({"history.csv", std::to_string(3 + c) + ":" + std::to_string(6 + c), "", names[c],
                           c == 0 ? "lines lw 2" : "lines"});
  // Markers only for the rows that occur, on the curve of the row's dominant normal stress.
  if (events & kOnsetRow) ss.series.push_back(marker(kOnsetRow, kDominantStrain, kDominantStress, "onset", "points pt 7 ps 1.5"));
  if (events & kPeakRow)
    ss.series.push_back(marker(kPeakRow, kDominantStrain, kDominantStress, "stress maximum inside an increment", "points pt 9 ps 1.5"));
  if (events & kLastStableRow)
    ss.series.push_back(
        marker(kLastStableRow, kDominantStrain, kDominantStress, "last stable state before a snap-back", "points pt 6 ps 2"));

  io::PlotSpec to;
  to.title = scene.name + ": traction-opening of the band" + (secondBand ? "s" : "");
  to.xLabel = secondBand ? "inelastic opening w = h (eps_L - C sigma)_nn, jump [u].n (mm)"
                         : "inelastic opening w = h (eps_L - C sigma)_nn (mm)";
  to.yLabel = secondBand ? "normal traction on the band n.sigma.n (MPa)" : "normal traction n.sigma.n (MPa)";
  to.series = {{"history.csv", "($9 > 0 ? $13 : 1/0):14", "", "traction vs opening w", "lines lw 2"},
               {"history.csv", "($9 > 0 ? $11 : 1/0):14", "", "traction vs jump [u].n", "lines dt 2"}};
  if (secondBand)  // history.csv's second-band columns: damage_2 25, jump_n_2 26, normal_x_2 28, normal_y_2 29
    to.series.push_back({"history.csv", "($25 > 0 ? $26 : 1/0):($28*$28*$6 + $29*$29*$7 + 2*$28*$29*$8)", "",
                         "second band: n2.sigma.n2 vs jump [u]_2.n2", "lines lw 2"});
  if (events & kLastStableRow)
    to.series.push_back(marker(kLastStableRow, "$13", "14", "last stable state before a snap-back", "points pt 6 ps 2"));
  return {ss, to};
}

void writePointPlots(const PointScene& scene, const PointRun& run, const std::filesystem::path& dir) {
  const std::vector<io::PlotSpec> specs = pointPlotSpecs(scene, run);
  io::renderPlot(specs[0], dir / "stress_strain.png");
  io::renderPlot(specs[1], dir / "traction_opening.png");
}

void writePointOutputs(const PointScene& scene, const PointRun& run, const std::filesystem::path& dir) {
  writeHistoryCsv(run, dir / "history.csv", scene.material.secondBand != SecondBandOption::Off);
  io::writeJsonSummary(pointSummaryJson(scene, run), dir / "summary.json");
  writePointPlots(scene, run, dir);
}

}  // namespace ecm::driver
