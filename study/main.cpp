// ecm-study: speed versus accuracy over a grid of scene settings (format in study/study.hpp).
//   ecm-study STUDY.yaml [-o|--out DIR] [--threads N] [--list] [--resume] [--in-process] [-q]
// Exit status (io/cli_exit.hpp): 0 every run completed, 1 some run failed (see study.csv) or an
// output could not be written once the runs had begun, 2 bad input or output folder.
#include <CLI/CLI.hpp>
#include <optional>
#include <cstdio>
#include <exception>
#include <iostream>

#include "io/cli_exit.hpp"
#include "io/command_line.hpp"
#include "io/output_dir.hpp"
#include "io/output_error.hpp"
#include "study/study.hpp"

int main(int argc, char** argv) {
  CLI::App app{"ecm-study: wall time, memory and error of a scene over a grid of settings (units: mm, N, MPa, t, s)"};
  std::string studyPath, outDir;
  ecm::study::StudyOptions options;
  bool list = false, inProcess = false, quiet = false, resume = false;
  app.add_option("study", studyPath, "study file (YAML)")->required()->check(CLI::ExistingFile);
  app.add_option("-o,--out", outDir, "output folder (default: out/STUDY-NAME)");
  app.add_option("-t,--threads", options.threads, "OpenMP threads of each MPM run (default 2)")->check(CLI::Range(1, 4096));
  app.add_flag("--list", list, "print the planned runs (checked like scenes) and stop");
  app.add_flag("--resume", resume, "reuse the MPM runs of DIR whose scene is unchanged (an interrupted study goes on)");
  app.add_flag("--in-process", inProcess, "run MPM scenes in this process (no per-run peak memory)");
  app.add_flag("-q,--quiet", quiet, "no line per run on stderr");
  if (const std::optional<int> status = ecm::io::parseCommandLine(app, "ecm-study", argc, argv)) return *status;

  bool running = false;  // input read and output folder ready: a failure from here on is the runs'
  try {
    const ecm::study::Study study = ecm::study::loadStudyFile(studyPath);
    const std::vector<ecm::study::PlannedRun> plan = ecm::study::planStudy(study);
    if (list) {
      const bool mpm = study.kind == ecm::study::StudyKind::Mpm;
      double total = 0.0;
      for (const auto& r : plan) {
        const double work = static_cast<double>(r.particles) * r.estimatedSteps;
        total += work;
        if (mpm)
          std::printf("%3d%s  %-60s  %8zu particles  %9.0f steps  %.3g particle-updates\n", r.id, r.reference ? "R" : " ",
                      r.label.c_str(), r.particles, r.estimatedSteps, work);
        else
          std::printf("%3d%s  %-60s  %9.0f increments\n", r.id, r.reference ? "R" : " ", r.label.c_str(), work);
      }
      std::printf("%zu runs, %.3g %s in all\n", plan.size(), total, mpm ? "particle-updates (estimated)" : "increments");
      return ecm::io::kExitDone;
    }
    options.outputDir = outDir.empty() ? std::filesystem::path("out") / study.name : std::filesystem::path(outDir);
    ecm::io::prepareOutputDir(options.outputDir);
    running = true;
    options.isolate = !inProcess;
    options.resume = resume;
    options.progress = !quiet;
    options.table = &std::cout;
    const ecm::study::StudyResult r = ecm::study::runStudy(study, plan, options);
    std::fprintf(stderr, "%zu runs -> %s (study.csv, summary.json, %s)\n", r.runs.size(), options.outputDir.string().c_str(),
                 r.ensemble.is_null() ? "pareto.png" : "ensemble.csv, ensemble_histogram.png, weibull.png");
    std::fputs(ecm::study::notCompletedList(r).c_str(), stderr);
    return r.allCompleted ? ecm::io::kExitDone : ecm::io::kExitRunFailed;
  } catch (const ecm::io::InputError& e) {
    ecm::io::printError("ecm-study", e.what());
    return ecm::io::kExitBadInput;
  } catch (const ecm::io::OutputError& e) {
    ecm::io::printError("ecm-study", e.what());
  } catch (const std::exception& e) {
    ecm::io::printError("ecm-study", studyPath + ": " + e.what());
  }
  return running ? ecm::io::kExitRunFailed : ecm::io::kExitBadInput;
}
