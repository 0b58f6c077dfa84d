// What a UMAT run leaves in its output folder (driver/umat_driver.hpp): history.csv row by row,
// summary.json and stress_strain.png at the end.
#include <algorithm>
#include <optional>

#include "driver/umat_driver.hpp"
#include "io/csv_writer.hpp"
#include "io/gnuplot.hpp"
#include "io/json_summary.hpp"

namespace ecm::driver {

struct UmatOutputs::Impl {
  const UmatScene& scene;
  std::filesystem::path dir;
  std::optional<io::CsvWriter> csv;
};

namespace {

std::vector<std::string> historyHeader(std::size_t nstatv) {
  std::vector<std::string> h{"increment", "segment", "eps_xx", "eps_yy", "eps_zz", "gamma_yz", "gamma_xz", "gamma_xy",
                             "sig_xx", "sig_yy", "sig_zz", "sig_yz", "sig_xz", "sig_xy", "work", "sse", "spd", "scd",
                             "iterations", "substeps"};
  for (std::size_t i = 1; i <= nstatv; ++i) h.push_back("statev_" + std::to_string(i));
  return h;
}

std::vector<double> voigtList(const Voigt6& v) { return {v.data(), v.data() + 6}; }

}  // namespace

UmatOutputs::UmatOutputs(const UmatScene& scene, const std::filesystem::path& dir) : impl_(new Impl{scene, dir, {}}) {
  impl_->csv.emplace(dir / "history.csv", historyHeader(scene.initialState.size()));
}

UmatOutputs::~UmatOutputs() = default;

void UmatOutputs::row(const UmatRow& r) {
  std::vector<double> v{double(r.increment), double(r.segment)};
  for (int i = 0; i < 6; ++i) v.push_back(r.strain[i]);
  for (int i = 0; i < 6; ++i) v.push_back(r.stress[i]);
  v.insert(v.end(), {r.work, r.sse, r.spd, r.scd, double(r.iterations), double(r.substeps)});
  v.insert(v.end(), r.state.begin(), r.state.end());
  impl_->csv->row(v);
  impl_->csv->flush();  // a UMAT may end the process (XIT): every row before it stays
}

void UmatOutputs::finish(const UmatRun& run, const UmatLibrary& library) {
  impl_->csv->close();
  const UmatScene& scene = impl_->scene;
  nlohmann::json j;
  j["units"] = "mm, N, MPa; energies per unit volume in MPa (N mm/mm^3); components in ecm's order (xx, yy, zz, yz, "
               "xz, xy; engineering shears)";
  j["scene"] = scene.name;
  j["hypothesis"] = "three_dimensional";
  j["umat"] = {{"library", library.file().string()},
               {"entry", library.entry()},
               {"props", scene.props},
               {"props_source", scene.propsSource},
               {"nstatv", scene.initialState.size()},
               {"celent", scene.characteristicLength},
               {"cmname", scene.materialName}};
  double peak = 0.0;
  for (const UmatRow& r : run.history) peak = std::max(peak, largestPrincipal(r.stress).first);
  j["peak_stress"] = peak;  // the largest principal stress over the rows (MPa)
  const UmatRow last = run.history.empty() ? UmatRow{} : run.history.back();
  j["increments"] = last.increment;
  j["work_per_volume"] = last.work;
  j["completed"] = run.completed;
  if (!run.completed) j["failure"] = run.failure;
  j["final"] = {{"strain", voigtList(last.strain)},
                {"stress", voigtList(last.stress)},
                {"statev", last.state},
                {"sse", last.sse},
                {"spd", last.spd},
                {"scd", last.scd}};
  io::writeJsonSummary(j, impl_->dir / "summary.json");
  io::PlotSpec ss;
  ss.title = scene.name + ": stress-strain of the UMAT " + library.file().filename().string();
  ss.xLabel = "eps_xx";
  ss.yLabel = "stress (MPa)";
  ss.series = {{"history.csv", "3:9", "", "sig_xx", "lines lw 2"}, {"history.csv", "3:10", "", "sig_yy", "lines"},
               {"history.csv", "3:11", "", "sig_zz", "lines"},   {"history.csv", "3:14", "", "sig_xy", "lines"}};
  io::renderPlot(ss, impl_->dir / "stress_strain.png");
  // Every stress against the increment: readable on any path (a shear segment at fixed eps_xx
  // is a vertical line in the plot above).
  io::PlotSpec sh;
  sh.title = scene.name + ": stresses along the path, UMAT " + library.file().filename().string();
  sh.xLabel = "increment";
  sh.yLabel = "stress (MPa)";
  const char* names[6] = {"sig_xx", "sig_yy", "sig_zz", "sig_yz", "sig_xz", "sig_xy"};
  for (int i = 0; i < 6; ++i)
    sh.series.push_back({"history.csv", "1:" + std::to_string(9 + i), "", names[i], i == 0 ? "lines lw 2" : "lines"});
  io::renderPlot(sh, impl_->dir / "stress_history.png");
}

}  // namespace ecm::driver
