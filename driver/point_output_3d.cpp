// What a 3D point run leaves in its output folder (driver/point_driver_3d.hpp).
#include <algorithm>

#include "driver/point_driver_3d.hpp"
#include "io/csv_writer.hpp"
#include "io/gnuplot.hpp"
#include "io/json_summary.hpp"

namespace ecm::driver {

namespace {

double normalTraction3(const HistoryRow3& r) {
  if (!r.crackNormal.any()) return r.stress[0];
  return r.crackNormal.dot(stressTensor(r.stress) * r.crackNormal);
}

double largestPrincipalStress(const HistoryRow3& r) { return largestPrincipal(r.stress).first; }

}  // namespace

void writePointOutputs3(const PointScene3& scene, const PointRun3& run, const std::filesystem::path& dir) {
  {
    io::CsvWriter csv(dir / "history.csv",
                      {"increment", "segment", "eps_xx", "eps_yy", "eps_zz", "gamma_yz", "gamma_xz", "gamma_xy", "sig_xx",
                       "sig_yy", "sig_zz", "sig_yz", "sig_xz", "sig_xy", "damage", "integrity", "jump_n", "jump_t",
                       "traction_n", "normal_x", "normal_y", "normal_z", "volume_fraction", "work", "dissipation",
                       "stored_energy", "iterations", "substeps", "snapback_release", "event"});
    for (const HistoryRow3& r : run.history) {
      std::vector<double> row{double(r.increment), double(r.segment)};
      for (int i = 0; i < 6; ++i) row.push_back(r.strain[i]);
      for (int i = 0; i < 6; ++i) row.push_back(r.stress[i]);
      row.insert(row.end(), {r.damage, r.integrity, r.normalJump, r.slidingJump, normalTraction3(r), r.crackNormal[0],
                             r.crackNormal[1], r.crackNormal[2], r.volumeFraction, r.work, r.dissipation, r.storedEnergy,
                             double(r.iterations), double(r.substeps), r.snapBackRelease ? 1.0 : 0.0, r.onset ? 1.0 : 0.0});
      csv.row(row);
    }
    csv.close();
  }
  nlohmann::json j;
  j["units"] = "mm, N, MPa; energies per unit volume in MPa (N mm/mm^3), H x energy in N/mm";
  j["scene"] = scene.name;
  j["hypothesis"] = "three_dimensional";
  j["model"] = toString(scene.material.model);
  j["material"] = scene.material.name;
  j["H"] = scene.effectiveSize;
  double peak = 0.0;
  for (const HistoryRow3& r : run.history) peak = std::max(peak, largestPrincipalStress(r));
  j["peak_stress"] = peak;
  const HistoryRow3 last = run.history.empty() ? HistoryRow3{} : run.history.back();
  j["dissipated_energy_per_volume"] = last.dissipation;
  j["H_times_dissipated_energy"] = scene.effectiveSize * last.dissipation;
  j["work_per_volume"] = last.work;
  j["increments"] = last.increment;
  j["completed"] = run.completed;
  if (!run.completed) j["failure"] = run.failure;
  j["final"] = {{"damage", last.damage},
                {"integrity", last.integrity},
                {"jump_n", last.normalJump},
                {"normal", {last.crackNormal[0], last.crackNormal[1], last.crackNormal[2]}}};
  io::writeJsonSummary(j, dir / "summary.json");

  io::PlotSpec ss;
  ss.title = scene.name + ": stress-strain, 3D (H = " + std::to_string(scene.effectiveSize) + " mm)";
  ss.xLabel = "eps_xx";
  ss.yLabel = "stress (MPa)";
  ss.series = {{"history.csv", "3:9", "", "sig_xx", "lines lw 2"}, {"history.csv", "3:10", "", "sig_yy", "lines"},
               {"history.csv", "3:11", "", "sig_zz", "lines"},   {"history.csv", "3:14", "", "sig_xy", "lines"},
               {"history.csv", "(int($30) & 1 ? $3 : 1/0):9", "", "onset", "points pt 7 ps 1.5"}};
  io::renderPlot(ss, dir / "stress_strain.png");
  io::PlotSpec to;
  to.title = scene.name + ": traction-jump of the band, 3D";
  to.xLabel = "normal jump [u].n (mm)";
  to.yLabel = "normal traction n.sigma.n (MPa)";
  to.series = {{"history.csv", "($15 > 0 ? $17 : 1/0):19", "", "traction vs jump [u].n", "lines lw 2"}};
  io::renderPlot(to, dir / "traction_opening.png");
}

}  // namespace ecm::driver
