// ecm-mpm: runs an MPM scene (YAML) and writes its output folder.
//   ecm-mpm SCENE.yaml [-o|--out DIR] [--threads N] [--no-vtu] [--no-plot] [--quiet] [--max-steps N]
//   ecm-mpm SCENE.yaml --restart DIR [...]      continue the run of DIR from DIR/checkpoint.bin
// SIGINT / SIGTERM stop the run after the current step with a checkpoint (a second one kills it).
// Exit status (io/cli_exit.hpp): 0 completed, 2 bad input (command line included), output folder
// or checkpoint, 3 stopped before the end with a checkpoint (signal or --max-steps): resume it,
// 10-20 the run failed, one status per failure kind (mpm/core/errors.hpp; summary.json's
// failure.kind names it).
#include <CLI/CLI.hpp>
#include <optional>
#include <atomic>
#include <csignal>
#include <cstdio>
#include <exception>
#include <fstream>
#include <iterator>

#include "io/checksum.hpp"
#include "io/cli_exit.hpp"
#include "io/command_line.hpp"
#include "io/output_error.hpp"
#include "io/yaml_input.hpp"
#include "mpm/output/checkpoint_codec.hpp"
#include "mpm/scene/presets.hpp"
#include "mpm/run.hpp"
#include "mpm/scene/scene_yaml.hpp"
#include "mpm/scene/unmeasured.hpp"

namespace {

std::atomic<bool> stopRequested{false};
static_assert(std::atomic<bool>::is_always_lock_free, "the signal handler needs a lock-free flag");

extern "C" void onStopSignal(int) { stopRequested.store(true, std::memory_order_relaxed); }

// SA_RESETHAND: a second signal takes the default action (the user insists: no checkpoint).
void installStopHandler() {
  struct sigaction sa = {};
  sa.sa_handler = onStopSignal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESTART | SA_RESETHAND;
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
  // A file size limit (ulimit -f) then fails the write (EFBIG), reported like a full disk,
  // instead of killing the run.
  std::signal(SIGXFSZ, SIG_IGN);
}

// A path as one shell word (quoted when it needs to be), for the resume command.
std::string shellWord(const std::string& s) {
  if (!s.empty() && s.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_-./+=:,@") ==
                        std::string::npos)
    return s;
  std::string q = "'";
  for (const char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

std::uint64_t fileHash(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  return ecm::io::fnv1a64(text);
}

std::vector<std::string> presetNameList() {
  std::vector<std::string> names;
  for (const ecm::mpm::Preset& p : ecm::mpm::presets()) names.emplace_back(p.name);
  return names;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"ecm-mpm: 2D MPM, explicit or implicit (quasi-static), with the enriched constitutive model (units: mm, N, MPa, t, s)"};
  std::string scenePath;
  ecm::mpm::RunOptions options;
  std::string outDir, restartDir, preset;
  bool noVtu = false, noPlot = false, quiet = false;
  app.add_option("scene", scenePath, "scene file (YAML)")->required()->check(CLI::ExistingFile);
  app.add_option("-o,--output,--out", outDir, "output folder (default: SCENE-NAME-out next to the working folder)");
  app.add_option("--restart", restartDir,
                 "continue the run of this output folder from its checkpoint.bin (with the same scene file)");
  app.add_option("-t,--threads", options.threads, "OpenMP threads (0: default)")->check(CLI::Range(0, 4096));
  app.add_option("--max-steps", options.maxSteps, "stop with a checkpoint once the run has made N steps (from t = 0)")
      ->check(CLI::Range(1L, 1'000'000'000'000L));
  app.add_option("--preset", preset,
                 ecm::mpm::presetNames() + ": particles per cell, shape function, scheme and CFL from the measured "
                 "speed/accuracy presets (mpm/scene/presets.hpp), replacing the scene's")
      ->check(CLI::IsMember(presetNameList()));
  app.add_flag("--no-vtu", noVtu, "do not write VTU particle snapshots");
  app.add_flag("--no-plot", noPlot, "do not render the load-displacement PNG");
  app.add_flag("-q,--quiet", quiet, "no progress on stderr");
  if (const std::optional<int> status = ecm::io::parseCommandLine(app, "ecm-mpm", argc, argv)) return *status;

  try {
    ecm::mpm::Scene scene = ecm::mpm::loadSceneFile(scenePath);
    if (!preset.empty()) ecm::mpm::applyPreset(*ecm::mpm::findPreset(preset), scene);
    for (const std::string& note : ecm::mpm::unmeasuredCombinations(scene))
      std::fprintf(stderr, "ecm-mpm: note: %s\n", note.c_str());
    if (!restartDir.empty()) {
      const auto normal = [](const std::string& p) { return std::filesystem::path(p).lexically_normal(); };
      if (!outDir.empty() && normal(outDir) != normal(restartDir)) {
        ecm::io::printError("ecm-mpm", "--restart " + restartDir + " continues that folder; --out " + outDir +
                                           " names another one");
        return ecm::io::kExitBadInput;
      }
      outDir = restartDir;
      options.restart = true;
    }
    options.outputDir = outDir.empty() ? std::filesystem::path(scene.name + "-out") : std::filesystem::path(outDir);
    options.snapshots = !noVtu;
    options.plot = !noPlot;
    options.progress = !quiet;
    options.sceneHash = fileHash(scenePath);
    if (!preset.empty()) options.sceneHash = ecm::io::fnv1a64(preset, options.sceneHash);  // a restart needs the same preset
    options.stop = &stopRequested;
    options.resumeCommand = "ecm-mpm " + shellWord(scenePath) + (preset.empty() ? "" : " --preset " + preset) +
                            " --restart " + shellWord(options.outputDir.string());
    installStopHandler();
    const ecm::mpm::RunResult r = ecm::mpm::runScene(scene, options);
    std::fprintf(stderr, "%s: %ld steps, %zu particles, peak load %.6g N, %.2f s -> %s\n",
                 r.completed ? (r.endedByStopWhen ? "completed (stop_when met)" : "completed")
                             : (r.stopped ? "STOPPED" : "FAILED"),
                 r.steps, r.particles, r.peakLoad, r.wallTime, options.outputDir.string().c_str());
    if (r.stopped && r.checkpoint.empty()) {  // (a scene with platens writes no checkpoint)
      std::fprintf(stderr, "stopped at step %ld (%s); no checkpoint to resume from\n", r.steps, stopRequested.load() ? "signal" : "--max-steps");
      return ecm::io::kExitStopped;
    }
    if (r.stopped) {
      std::fprintf(stderr, "stopped at step %ld (%s); checkpoint %s\nresume with: %s\n", r.steps,
                   stopRequested.load() ? "signal" : "--max-steps", r.checkpoint.string().c_str(),
                   options.resumeCommand.c_str());
      return ecm::io::kExitStopped;
    }
    if (!r.completed) {
      ecm::io::printError("ecm-mpm", r.message());
      if (!r.checkpoint.empty())
        std::fprintf(stderr, "the last checkpoint is %s (resume with: %s)\n", r.checkpoint.string().c_str(),
                     options.resumeCommand.c_str());
      return r.failure ? ecm::mpm::exitStatusOf(r.failure->kind) : ecm::io::kExitRunFailed;
    }
    return ecm::io::kExitDone;
  } catch (const ecm::io::InputError& e) {
    ecm::io::printError("ecm-mpm", e.what());
  } catch (const ecm::io::OutputError& e) {
    ecm::io::printError("ecm-mpm", e.what());
  } catch (const ecm::mpm::CheckpointError& e) {
    ecm::io::printError("ecm-mpm", e.what());
  } catch (const std::exception& e) {
    ecm::io::printError("ecm-mpm", scenePath + ": " + e.what());
  }
  return ecm::io::kExitBadInput;  // runScene reports a failure during the run in its result
}
