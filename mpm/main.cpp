// ecm-mpm: runs an MPM scene (YAML) and writes its output folder.
//   ecm-mpm SCENE.yaml [-o|--out DIR] [--threads N] [--no-vtu] [--no-plot] [--quiet]
// Exit status: 0 completed, 1 the run failed (see summary.json), 2 bad input or output folder.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>

#include "io/output_error.hpp"
#include "io/yaml_input.hpp"
#include "mpm/run.hpp"
#include "mpm/scene_yaml.hpp"

int main(int argc, char** argv) {
  CLI::App app{"ecm-mpm: explicit MPM with the enriched constitutive model (units: mm, N, MPa, t, s)"};
  std::string scenePath;
  ecm::mpm::RunOptions options;
  std::string outDir;
  bool noVtu = false, noPlot = false, quiet = false;
  app.add_option("scene", scenePath, "scene file (YAML)")->required()->check(CLI::ExistingFile);
  app.add_option("-o,--output,--out", outDir, "output folder (default: SCENE-NAME-out next to the working folder)");
  app.add_option("-t,--threads", options.threads, "OpenMP threads (0: default)")->check(CLI::NonNegativeNumber);
  app.add_flag("--no-vtu", noVtu, "do not write VTU particle snapshots");
  app.add_flag("--no-plot", noPlot, "do not render the load-displacement PNG");
  app.add_flag("-q,--quiet", quiet, "no progress on stderr");
  CLI11_PARSE(app, argc, argv);

  try {
    const ecm::mpm::Scene scene = ecm::mpm::loadSceneFile(scenePath);
    options.outputDir = outDir.empty() ? std::filesystem::path(scene.name + "-out") : std::filesystem::path(outDir);
    options.snapshots = !noVtu;
    options.plot = !noPlot;
    options.progress = !quiet;
    const ecm::mpm::RunResult r = ecm::mpm::runScene(scene, options);
    std::fprintf(stderr, "%s: %ld steps, %zu particles, peak load %.6g N, %.2f s -> %s\n",
                 r.completed ? "completed" : "FAILED", r.steps, r.particles, r.peakLoad, r.wallTime,
                 options.outputDir.string().c_str());
    if (!r.completed) {
      std::fprintf(stderr, "error: %s\n", r.error.c_str());
      return 1;
    }
    return 0;
  } catch (const ecm::io::InputError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
  } catch (const ecm::io::OutputError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s: %s\n", scenePath.c_str(), e.what());
  }
  return 2;
}
