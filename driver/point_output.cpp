#include "driver/point_output.hpp"

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

void writePointPlots(const PointScene& scene, const std::filesystem::path& dir) {
  io::PlotSpec ss;
  ss.title = scene.name + ": stress-strain (H = " + std::to_string(scene.effectiveSize) + " mm)";
  ss.xLabel = "eps_xx";
  ss.yLabel = "stress (MPa)";
  ss.series = {{"history.csv", "3:6", "", "sig_xx", "lines lw 2"},
               {"history.csv", "3:7", "", "sig_yy", "lines"},
               {"history.csv", "3:8", "", "sig_xy", "lines"},
               {"history.csv", "(int($24) & 1 ? $3 : 1/0):6", "", "onset", "points pt 7 ps 1.5"},
               {"history.csv", "(int($24) & 4 ? $3 : 1/0):6", "", "stress maximum inside an increment", "points pt 9 ps 1.5"},
               {"history.csv", "(int($24) & 2 ? $3 : 1/0):6", "", "last stable state before a snap-back", "points pt 6 ps 2"}};
  io::renderPlot(ss, dir / "stress_strain.png");
  io::PlotSpec to;
  to.title = scene.name + ": traction-opening of the band";
  to.xLabel = "inelastic opening w = h (eps_L - C sigma)_nn (mm)";
  to.yLabel = "normal traction n.sigma.n (MPa)";
  to.series = {{"history.csv", "($9 > 0 ? $13 : 1/0):14", "", "traction vs opening w", "lines lw 2"},
               {"history.csv", "($9 > 0 ? $11 : 1/0):14", "", "traction vs jump [u].n", "lines dt 2"},
               {"history.csv", "(int($24) & 2 ? $13 : 1/0):14", "", "last stable state before a snap-back", "points pt 6 ps 2"}};
  io::renderPlot(to, dir / "traction_opening.png");
}

void writePointOutputs(const PointScene& scene, const PointRun& run, const std::filesystem::path& dir) {
  writeHistoryCsv(run, dir / "history.csv", scene.material.secondBand != SecondBandOption::Off);
  io::writeJsonSummary(pointSummaryJson(scene, run), dir / "summary.json");
  writePointPlots(scene, dir);
}

}  // namespace ecm::driver
