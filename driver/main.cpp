// ecm-point: drive one material point along a strain path.
//   ecm-point SCENE.yaml [--out DIR]
//   ecm-point --study STUDY.yaml [--out DIR]     (the snap-back study over effective sizes)
//   ecm-point SCENE.yaml --umat LIB.so [--out DIR]  (a UMAT along the 3D paths)
// Exit status (io/cli_exit.hpp): 0 done, 1 the run stopped early or an output could not be
// written (outputs so far kept), 2 bad input or output folder.
#include <CLI/CLI.hpp>
#include <optional>

#include <iostream>

#include "driver/point_driver_3d.hpp"
#include "driver/point_output.hpp"
#include "driver/point_scene_yaml.hpp"
#include "driver/snapback_study.hpp"
#include "driver/umat_driver.hpp"
#include "io/cli_exit.hpp"
#include "io/command_line.hpp"
#include "io/output_dir.hpp"
#include "io/progress.hpp"

int main(int argc, char** argv) {
  CLI::App app{"ecm-point: single-point strain-path driver for the enriched, smeared-crack and elastic models"};
  std::string scene, study, out, umat;
  app.add_option("scene", scene, "point scene (YAML)")->check(CLI::ExistingFile);
  app.add_option("--study", study, "snap-back study over effective sizes (YAML)")->check(CLI::ExistingFile);
  app.add_option("--umat", umat,
                 "drive this UMAT library (Abaqus interface) along the scene's 3D path: PROPS and NSTATV from the "
                 "scene's umat: block, or ecm's PROPS for the scene's material")
      ->check(CLI::ExistingFile);
  app.add_option("--out", out, "output folder (default out/point/<scene name> or out/snapback-study)");
  if (const std::optional<int> status = ecm::io::parseCommandLine(app, "ecm-point", argc, argv)) return *status;
  if (scene.empty() == study.empty()) {
    ecm::io::printError("ecm-point", "give either a SCENE.yaml or --study STUDY.yaml");
    std::cerr << "Run with --help for more information.\n";
    return ecm::io::kExitBadInput;
  }
  if (!umat.empty() && !study.empty()) {
    ecm::io::printError("ecm-point", "--umat drives one scene, not a --study");
    return ecm::io::kExitBadInput;
  }
  bool running = false;  // input read and output folder ready: a failure from here on is the run's
  try {
    if (study.empty() && (!umat.empty() || ecm::driver::isUmatScene(ecm::io::loadYamlFile(scene)))) {
      const ecm::io::YamlMap map = ecm::io::loadYamlFile(scene);
      if (umat.empty()) {
        ecm::io::printError("ecm-point", scene + ": this scene drives a UMAT (umat:): give its library with --umat LIB.so");
        return ecm::io::kExitBadInput;
      }
      ecm::driver::UmatScene s;
      if (ecm::driver::isUmatScene(map)) {
        s = ecm::driver::readUmatScene(map);
      } else if (ecm::driver::isThreeDimensionalScene(map)) {
        s = ecm::driver::umatSceneFor(ecm::driver::readPointScene3(map));
      } else {
        ecm::io::printError("ecm-point", scene + ": --umat drives 3D paths: give a umat: block, or a material scene with "
                                                 "hypothesis: three_dimensional");
        return ecm::io::kExitBadInput;
      }
      const ecm::driver::UmatLibrary library(umat);
      const auto dir = ecm::io::prepareOutputDir(out.empty() ? "out/point/" + std::filesystem::path(scene).stem().string() : out);
      running = true;
      ecm::driver::UmatOutputs outputs(s, dir);
      ecm::io::Progress::Options options;
      options.label = "ecm-point " + s.name + " (UMAT " + library.file().filename().string() + ")";
      int total = 0;
      for (const auto& segment : s.path) total += segment.increments;
      ecm::io::Progress progress(total, options);
      const ecm::driver::UmatRun run = ecm::driver::runUmat(s, library, [&](const ecm::driver::UmatRow& row, int done, int) {
        outputs.row(row);
        progress.update(done);
      });
      progress.finish();
      outputs.finish(run, library);
      std::cout << "outputs in " << dir.string() << "\n";
      if (!run.completed) {
        ecm::io::printError("ecm-point", "run stopped: " + run.failure + " (everything up to it is in " + dir.string() + ")");
        return ecm::io::kExitRunFailed;
      }
      return ecm::io::kExitDone;
    }
    if (!study.empty()) {
      const ecm::driver::SnapBackStudy s = ecm::driver::loadSnapBackStudy(study);
      const auto dir = ecm::io::prepareOutputDir(out.empty() ? "out/snapback-study" : out);
      running = true;
      const ecm::driver::SnapBackStudyResult r = ecm::driver::runSnapBackStudy(s, dir, std::cout);
      return r.allRunsCompleted ? ecm::io::kExitDone : ecm::io::kExitRunFailed;
    }
    if (ecm::driver::isThreeDimensionalScene(ecm::io::loadYamlFile(scene))) {
      const ecm::driver::PointScene3 s = ecm::driver::loadPointScene3(scene);
      const auto dir = ecm::io::prepareOutputDir(out.empty() ? "out/point/" + std::filesystem::path(scene).stem().string() : out);
      running = true;
      ecm::io::Progress::Options options;
      options.label = "ecm-point " + s.name + " (3D)";
      ecm::io::Progress progress(ecm::driver::totalIncrements(s), options);
      const ecm::driver::PointRun3 run = ecm::driver::runPoint3D(s, [&](const ecm::driver::HistoryRow3&, int done, int) { progress.update(done); });
      progress.finish();
      ecm::driver::writePointOutputs3(s, run, dir);
      std::cout << "outputs in " << dir.string() << "\n";
      if (!run.completed) {
        std::cerr << "ecm-point: run stopped: " << run.failure << " (everything up to it is in " << dir.string() << ")\n";
        return ecm::io::kExitRunFailed;
      }
      return ecm::io::kExitDone;
    }
    const ecm::driver::PointScene s = ecm::driver::loadPointScene(scene);
    const auto dir = ecm::io::prepareOutputDir(out.empty() ? "out/point/" + std::filesystem::path(scene).stem().string() : out);
    running = true;
    ecm::io::Progress::Options options;
    options.label = "ecm-point " + s.name;
    ecm::io::Progress progress(ecm::driver::totalIncrements(s), options);
    const ecm::driver::PointRun run = ecm::driver::runPoint(s, [&](const ecm::driver::HistoryRow&, int done, int) { progress.update(done); });
    progress.finish();
    ecm::driver::writePointOutputs(s, run, dir);
    const ecm::driver::PointSummary sum = ecm::driver::summarise(s, run);
    std::cout << "peak stress " << sum.peakStress << " MPa at strain " << sum.strainAtPeak << "; H x dissipation "
              << sum.energyPerArea << " N/mm";
    if (s.material.fractureEnergy > 0.0) std::cout << " (" << sum.energyPerArea / s.material.fractureEnergy << " G_F)";
    std::cout << "\n";
    if (run.snapBack.detected)
      std::cout << "snap-back detected at increment " << run.snapBack.increment << " (stress " << run.snapBack.stressBefore
                << " MPa" << (run.snapBack.jumped ? ", drops to " + std::to_string(run.snapBack.stressAfter) + " MPa" : "")
                << ")\n";
    std::cout << "outputs in " << dir.string() << "\n";
    if (!run.completed) {
      ecm::io::printError("ecm-point", "run stopped: " + run.failure + " (everything up to it is in " + dir.string() + ")");
      return ecm::io::kExitRunFailed;
    }
    return ecm::io::kExitDone;
  } catch (const std::exception& e) {
    ecm::io::printError("ecm-point", e.what());
    return running ? ecm::io::kExitRunFailed : ecm::io::kExitBadInput;
  }
}
