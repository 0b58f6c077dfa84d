// ecm-cohesive: the cohesive-crack reference (plane-stress Q4 half model, a cohesive interface on
// the known crack path, Newton under CMOD or edge-displacement control). A thin main over the
// cohesive library; see docs/cohesive.md. Exit status (io/cli_exit.hpp): 0 done, 1 the run
// failed (outputs so far kept), 2 bad input or output folder.
#include <CLI/CLI.hpp>

#include <chrono>
#include <iostream>
#include <optional>

#include "cohesive/report.hpp"
#include "cohesive/scene.hpp"
#include "cohesive/solver.hpp"
#include "io/cli_exit.hpp"
#include "io/command_line.hpp"
#include "io/json_summary.hpp"
#include "io/output_dir.hpp"
#include "io/yaml_input.hpp"

namespace {

using namespace ecm;
using namespace ecm::cohesive;

int run(const std::filesystem::path& sceneFile, const std::filesystem::path& out, const SceneOverrides& overrides, bool& running) {
  const Scene scene = readScene(sceneFile, overrides);
  const HalfModel model = buildModel(scene);
  io::prepareOutputDir(out);
  running = true;
  std::cout << "ecm-cohesive: " << scene.name << ", law " << lawName(scene.law.kind) << ", cell " << scene.cellSize << " mm: "
            << model.mesh.elements.size() << " elements, " << model.equations << " dofs, " << model.interface.size()
            << " interface nodes\n";
  if (scene.law.kind == LawKind::table)
    std::cout << "  table " << scene.law.table.source << ": " << scene.law.table.opening.size() << " rows to opening "
              << scene.law.table.endOpening() << " mm, area " << scene.law.energyToFailure() << " N/mm (material.fracture_energy "
              << scene.fractureEnergy << " N/mm)\n";
  HistoryWriter history(out / "history.csv", model);
  const auto start = std::chrono::steady_clock::now();
  RunInfo info;
  SolveResult result;
  try {
    result = solveControlled(model, scene.law, scene.solver, [&](const StepRecord& r) { history.write(r); });
  } catch (const SolveFailure& f) {
    info.completed = false;
    info.failure = f.what();
    result = f.partial;
  }
  info.wallSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const nlohmann::json summary = runSummary(scene, model, result, info);
  io::writeJsonSummary(summary, out / "summary.json");
  if (!result.ligament.empty()) writeLigament(out / "ligament.csv", result);
  plotLoadCurve(out, scene, model);
  std::cout.precision(6);
  std::cout << "  peak P = " << summary["peak_load"].get<double>() << " N at " << model.controlName << " = "
            << summary["control_at_peak"].get<double>() << " mm; " << summary["steps"] << " steps, largest energy-balance error "
            << summary["max_balance_error"].get<double>() << ", " << info.wallSeconds << " s\n";
  std::cout << "  outputs in " << out.string() << ": history.csv, ligament.csv, summary.json, load.png\n";
  if (!info.completed) {
    io::printError("ecm-cohesive", info.failure);
    return io::kExitRunFailed;
  }
  return io::kExitDone;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "ecm-cohesive: cohesive-crack reference on a known crack path (units: mm, N, MPa).\n"
      "  ecm-cohesive data/reference/beam-hordijk-node.yaml --out out/beam [--cell 0.625] [--law band]\n"
      "Exit status: 0 done, 1 the run failed (outputs so far kept), 2 bad input."};
  app.set_help_flag("--help", "Print this help and exit");
  std::filesystem::path sceneFile, out;
  std::optional<double> cell;
  std::string law;
  app.add_option("scene", sceneFile, "the scene (YAML)")->required();
  app.add_option("--out", out, "output folder")->required();
  app.add_option("--cell", cell, "target cell size (mm), overrides the scene's cell");
  app.add_option("--law", law, "band | hordijk | table, overrides the scene's law");
  if (const std::optional<int> status = io::parseCommandLine(app, "ecm-cohesive", argc, argv)) return *status;
  SceneOverrides overrides;
  overrides.cellSize = cell;
  if (app.count("--law") > 0) {
    if (law != "band" && law != "hordijk" && law != "table") {
      io::printError("ecm-cohesive", "--law '" + law + "' is not one of: band, hordijk, table");
      return io::kExitBadInput;
    }
    overrides.law = law == "band" ? LawKind::band : law == "hordijk" ? LawKind::hordijk : LawKind::table;
  }
  bool running = false;
  try {
    return run(sceneFile, out, overrides, running);
  } catch (const io::InputError& e) {
    io::printError("ecm-cohesive", e.what());
    return io::kExitBadInput;
  } catch (const std::exception& e) {  // io::OutputError, a mesh that cannot hold the problem
    io::printError("ecm-cohesive", e.what());
    return running ? io::kExitRunFailed : io::kExitBadInput;
  }
}
