#include "cohesive/report.hpp"

#include <algorithm>
#include <cmath>

#include "io/gnuplot.hpp"
#include "io/json_summary.hpp"

namespace ecm::cohesive {

HistoryWriter::HistoryWriter(const std::filesystem::path& path, const HalfModel& model)
    : csv_(path, {"step", model.controlName, "P", "load_displacement", "dissipation", "bulk_energy", "interface_energy",
                  "external_work", "balance_error", "iterations"}) {}

void HistoryWriter::write(const StepRecord& r) {
  csv_.row({static_cast<double>(r.step), r.control, r.load, r.loadDisplacement, r.dissipation, r.bulkEnergy, r.interfaceEnergy,
            r.externalWork, r.balanceError, static_cast<double>(r.iterations)});
  csv_.flush();
}

std::optional<double> loadAt(const std::vector<StepRecord>& h, double control) {
  for (std::size_t k = 1; k < h.size(); ++k) {
    const double a = h[k - 1].control, b = h[k].control;
    if ((a - control) * (b - control) <= 0.0 && a != b) return h[k - 1].load + (control - a) / (b - a) * (h[k].load - h[k - 1].load);
  }
  return std::nullopt;
}

nlohmann::json runSummary(const Scene& scene, const HalfModel& model, const SolveResult& result, const RunInfo& info) {
  nlohmann::json j;
  j["name"] = scene.name;
  j["scene"] = scene.file;
  j["units"] = "mm, N, MPa";
  j["law"] = lawName(scene.law.kind);
  if (scene.law.kind == LawKind::hordijk) j["initial_stiffness"] = scene.law.hordijk.initialStiffness;
  if (scene.law.kind == LawKind::table) {
    // A table stops at a finite opening: its area is what it can dissipate, not G_F.
    const TableInterface& t = scene.law.table;
    j["initial_stiffness"] = t.initialStiffness;
    j["table"] = {{"file", t.source}, {"rows", t.opening.size()}, {"end_opening", t.endOpening()},
                  {"elastic_limit", t.elasticLimit()}, {"area", scene.law.energyToFailure()}};
  }
  j["control"] = model.controlName;
  j["completed"] = info.completed;
  if (!info.completed) j["failure"] = info.failure;
  const auto& h = result.history;
  const auto peak = std::max_element(h.begin(), h.end(), [](const StepRecord& a, const StepRecord& b) { return a.load < b.load; });
  j["peak_load"] = peak->load;
  j["control_at_peak"] = peak->control;
  for (const double c : {0.05, 0.1, 0.2}) {
    const auto p = loadAt(h, c);
    char key[32];
    std::snprintf(key, sizeof key, "P_at_%s_%g", model.controlName.c_str(), c);
    j[key] = p ? nlohmann::json(*p) : nlohmann::json(nullptr);
  }
  const double energy = scene.law.energyToFailure();
  j["final_control"] = h.back().control;
  j["dissipation"] = h.back().dissipation;
  j["dissipation_over_GF_area"] = h.back().dissipation / (scene.fractureEnergy * model.ligamentArea);
  j["energy_to_failure_per_area"] = energy;
  j["ligament_area"] = model.ligamentArea;
  double worst = 0.0;
  for (const StepRecord& r : h) worst = std::max(worst, r.balanceError);
  j["max_balance_error"] = worst;
  j["final_balance_error"] = h.back().balanceError;
  j["steps"] = h.size() - 1;
  int iterations = 0;
  for (const StepRecord& r : h) iterations += r.iterations;
  j["newton_iterations"] = iterations;
  j["wall_seconds"] = info.wallSeconds;
  j["cell_size"] = scene.cellSize;
  j["elements"] = model.mesh.elements.size();
  j["nodes"] = model.mesh.nodes.size();
  j["dofs"] = model.equations;
  j["interface_nodes"] = model.interface.size();
  return j;
}

void writeLigament(const std::filesystem::path& path, const SolveResult& result) {
  io::CsvWriter csv(path, {"position", "opening", "traction", "dissipation_per_area"});
  for (const InterfaceSample& s : result.ligament) csv.row({s.position, s.opening, s.traction, s.dissipation});
  csv.close();
}

void plotLoadCurve(const std::filesystem::path& dir, const Scene& scene, const HalfModel& model) {
  io::PlotSpec spec;
  const char* law = scene.law.kind == LawKind::band ? "band law" : scene.law.kind == LawKind::hordijk ? "Hordijk" : "table";
  spec.title = scene.name + ": cohesive reference (" + law + ")";
  spec.xLabel = model.controlName + " (mm)";
  spec.yLabel = "P (N)";
  spec.series.push_back({"history.csv", "2:3", "", "P", "lines lw 2"});
  io::renderPlot(spec, dir / "load.png");
}

}  // namespace ecm::cohesive
