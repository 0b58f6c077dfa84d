// ecm-study: running the plan (runStudy): each run into its own folder, an mpm run in a child
// process (or in-process), a point run in-process; its wall time, memory and errors.
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <numeric>
#include <stdexcept>

#include "driver/point_output.hpp"
#include "io/atomic_file.hpp"
#include "io/json_summary.hpp"
#include "io/output_dir.hpp"
#include "mpm/run.hpp"
#include "mpm/scene/scene_yaml.hpp"
#include "study/study.hpp"
#include "study/internal.hpp"

namespace ecm::study {

using namespace detail;

// ---------------------------------------------------------------------------------------------
// Running

namespace {

std::string sanitize(const std::string& label) {
  std::string s;
  for (const char c : label) {
    if (std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '=' || c == '-' || c == '_') s += c;
    else if (c == ' ' || c == ',') s += '_';
  }
  return s.substr(0, 80);
}

double parentRssMb() {
  std::ifstream statm("/proc/self/statm");
  long pages = 0, resident = 0;
  if (!(statm >> pages >> resident)) return NAN;
  return static_cast<double>(resident) * static_cast<double>(::sysconf(_SC_PAGESIZE)) / (1024.0 * 1024.0);
}

double jsonNumber(const nlohmann::json& j, const char* key) {
  const auto it = j.find(key);
  return it != j.end() && it->is_number() ? it->get<double>() : NAN;
}

// What the reference of a study provides to the error measures.
struct ReferenceData {
  bool available = false;
  double peakLoad = NAN, peakReaction = NAN, dissipated = NAN;  // mpm run reference
  LoadCurve curve;                                   // mpm run reference with a condition
  driver::PointRun point;                            // point run reference
  std::vector<double> pathParameter;         // point: strain path arc length of the reference rows
  double peakStress = NAN;
};

// Arc length of the strain path along the rows (engineering shear components).
std::vector<double> strainArcLength(const driver::PointRun& run) {
  std::vector<double> s;
  double total = 0.0;
  for (std::size_t i = 0; i < run.history.size(); ++i) {
    if (i > 0) total += (run.history[i].strain - run.history[i - 1].strain).norm();
    s.push_back(total);
  }
  return s;
}

double relative(double value, double reference) {
  return std::isfinite(value) && std::isfinite(reference) && reference != 0.0 ? value / reference - 1.0 : NAN;
}

class Executor {
 public:
  Executor(const Study& s, const StudyOptions& o, const std::filesystem::path& dir) : study_(s), options_(o), dir_(dir) {}

  RunRecord run(const PlannedRun& p, ReferenceData& ref, nlohmann::json& refJson) {
    RunRecord r;
    r.id = p.id;
    r.label = p.label;
    r.values = p.values;
    r.reference = p.reference;
    r.directory = runDirectory(p);
    r.metrics.assign(study_.metrics.size(), NAN);
    const std::filesystem::path dir = io::prepareOutputDir(dir_ / r.directory);
    std::error_code ec;
    const bool collect = options_.collectOnly && study_.kind == StudyKind::Mpm;
    // (collected: study_run.json marks a folder written whole; a run without summary.json then
    // fails with its error.txt, as a run of this process does)
    const bool reuse = (options_.resume || collect) && study_.kind == StudyKind::Mpm &&
                       std::filesystem::exists(dir / "scene.yaml", ec) && readText(dir / "scene.yaml") == p.sceneText &&
                       std::filesystem::exists(dir / "study_run.json", ec) &&
                       (collect || std::filesystem::exists(dir / "summary.json", ec));
    if (collect && !reuse) {
      r.status = "failed";
      r.message = "not run: no outputs of this scene in " + r.directory;
      return r;
    }
    if (!reuse) io::writeFileAtomically(dir / "scene.yaml", p.sceneText);
    r.reused = reuse && !collect;
    if (study_.kind == StudyKind::Mpm) runMpm(p, dir, reuse, r, ref, refJson);
    else runPointScene(p, dir, r, ref, refJson);
    double worst = NAN;
    for (const double m : r.metrics)
      if (std::isfinite(m)) worst = std::isnan(worst) ? std::abs(m) : std::max(worst, std::abs(m));
    bool all = true;
    for (const double m : r.metrics) all = all && std::isfinite(m);
    r.error = all ? worst : NAN;
    return r;
  }

 private:
  const Study& study_;
  const StudyOptions& options_;
  std::filesystem::path dir_;

  void setMetric(RunRecord& r, const std::string& name, double value) const {
    for (std::size_t i = 0; i < study_.metrics.size(); ++i)
      if (study_.metrics[i] == name) r.metrics[i] = value;
  }

  struct Usage {
    double peakRssMb = NAN, cpuTime = NAN;
  };

  // One execution of an mpm run; when isolated, the peak RSS (MB) and CPU time (s) of its process.
  Usage executeMpm(const mpm::Scene& scene, const std::filesystem::path& dir) const {
    mpm::RunOptions o;
    o.outputDir = dir;
    o.threads = options_.threads;
    o.snapshots = false;
    o.plot = false;
    o.progress = false;
    if (!options_.isolate) {
      try {
        mpm::runScene(scene, o);
      } catch (const std::exception& e) {  // an invalid scene (e.g. seeding): the run fails, the study goes on
        std::ofstream(dir / "error.txt") << e.what() << "\n";
      }
      return {};
    }
    std::fflush(nullptr);
    std::cout.flush();
    std::cerr.flush();
    const pid_t pid = ::fork();
    if (pid < 0) throw std::runtime_error("fork failed: cannot start a run");
    if (pid == 0) {
      ::prctl(PR_SET_PDEATHSIG, SIGTERM);  // a run does not outlive its study
      int code = 3;
      try {
        code = mpm::runScene(scene, o).completed ? 0 : 1;
      } catch (const std::exception& e) {
        std::ofstream(dir / "error.txt") << e.what() << "\n";
      } catch (...) {
        std::ofstream(dir / "error.txt") << "unknown exception\n";
      }
      ::_exit(code);
    }
    int status = 0;
    struct rusage usage {};
    while (::wait4(pid, &status, 0, &usage) < 0) {
      if (errno != EINTR) throw std::runtime_error("waiting for a run failed");
    }
    if (WIFSIGNALED(status))
      std::ofstream(dir / "error.txt") << "the run's process was killed by signal " << WTERMSIG(status) << "\n";
    auto seconds = [](const timeval& t) { return static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_usec); };
    return {static_cast<double>(usage.ru_maxrss) / 1024.0,  // Linux: kilobytes
            seconds(usage.ru_utime) + seconds(usage.ru_stime)};
  }

  // What an mpm run's outputs give the error measures.
  struct MpmOutcome {
    double peakLoad = NAN, peakReaction = NAN, dissipated = NAN;
  };

  // Fills r from the run's summary.json; false (r failed, with the reason) when there is none.
  static bool readSummary(const std::filesystem::path& dir, RunRecord& r, MpmOutcome& out) {
    nlohmann::json j;
    try {
      std::ifstream in(dir / "summary.json");
      if (!in) throw std::runtime_error("no summary.json");
      j = nlohmann::json::parse(in);
    } catch (const std::exception& e) {
      r.status = "failed";
      std::ifstream err(dir / "error.txt");
      std::string why;
      std::getline(err, why);
      r.message = why.empty() ? std::string("the run left no summary: ") + e.what() : why;
      return false;
    }
    r.status = j.value("status", std::string("failed"));
    r.message = j.value("error", std::string());
    r.wallTime = jsonNumber(j, "wall_time_s");
    r.updatesPerSecond = jsonNumber(j, "particle_updates_per_s");
    r.steps = jsonNumber(j, "steps");
    r.particles = jsonNumber(j, "particles");
    r.substepped = jsonNumber(j, "substepped_updates");
    const double intact = jsonNumber(j, "bytes_per_particle_uncracked"), cracked = jsonNumber(j, "bytes_per_particle_cracked");
    const double crackedCount = jsonNumber(j, "cracked_particles");
    if (r.particles > 0.0) r.bytesPerParticle = intact + (cracked - intact) * crackedCount / r.particles;
    out.peakLoad = jsonNumber(j, "peak_load");
    if (j.contains("energies_Nmm")) out.dissipated = jsonNumber(j["energies_Nmm"], "dissipated");
    return true;
  }

  // The largest |reaction| of a condition over the rows of history.csv.
  static double peakReaction(const io::CsvTable& h, const std::string& condition) {
    const auto x = std::find(h.header.begin(), h.header.end(), condition + "_rx_N") - h.header.begin();
    const auto y = std::find(h.header.begin(), h.header.end(), condition + "_ry_N") - h.header.begin();
    if (static_cast<std::size_t>(x) >= h.header.size() || static_cast<std::size_t>(y) >= h.header.size())
      throw std::runtime_error("no columns " + condition + "_rx_N, " + condition + "_ry_N");
    double peak = 0.0;
    for (const auto& row : h.rows) peak = std::max(peak, std::hypot(row[static_cast<std::size_t>(x)], row[static_cast<std::size_t>(y)]));
    return peak;
  }

  void runMpm(const PlannedRun& p, const std::filesystem::path& dir, bool reuse, RunRecord& r, ReferenceData& ref,
              nlohmann::json& refJson) const {
    std::error_code ec;
    MpmOutcome out;
    if (reuse) {  // --resume: the outputs of an earlier study of the same scene text
      std::ifstream in(dir / "study_run.json");
      const nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
      if (!readSummary(dir, r, out)) return;
      r.wallTime = jsonNumber(j, "wall_time_s");
      r.updatesPerSecond = jsonNumber(j, "updates_per_s");
      r.peakRssMb = jsonNumber(j, "peak_rss_mb");
      r.cpuTime = jsonNumber(j, "cpu_time_s");
    } else {
      double wall = NAN, ups = NAN, cpu = NAN;
      for (int rep = 0; rep < study_.repeat; ++rep) {
        std::filesystem::remove(dir / "summary.json", ec);
        std::filesystem::remove(dir / "error.txt", ec);
        std::filesystem::remove(dir / "study_run.json", ec);
        const Usage use = executeMpm(*p.scene, dir);
        if (std::isfinite(use.peakRssMb)) r.peakRssMb = std::isnan(r.peakRssMb) ? use.peakRssMb : std::max(r.peakRssMb, use.peakRssMb);
        r.cpuTime = use.cpuTime;
        if (!readSummary(dir, r, out)) return;
        if (std::isnan(wall) || r.wallTime < wall) wall = r.wallTime, ups = r.updatesPerSecond, cpu = use.cpuTime;
        if (r.status != "completed") break;
      }
      r.wallTime = wall;
      r.updatesPerSecond = ups;
      r.cpuTime = cpu;
      io::writeJsonSummary({{"wall_time_s", jsonValue(r.wallTime)},
                            {"updates_per_s", jsonValue(r.updatesPerSecond)},
                            {"peak_rss_mb", jsonValue(r.peakRssMb)},
                            {"cpu_time_s", jsonValue(r.cpuTime)},
                            {"repeat", study_.repeat}},
                           dir / "study_run.json");
    }
    if (r.status != "completed") return;
    if (study_.reference == ReferenceKind::BarVibration) {
      const BarVibration cf = barVibrationClosedForm(*p.scene);
      refJson = {{"closed_form", "bar_vibration"},
                 {"condition", study_.condition},
                 {"period_s", cf.period},
                 {"reaction_amplitude_N", cf.amplitude},
                 {"formula", "T = 4 L / c, R = rho c v0 A, c = sqrt(E / rho)"}};
      try {
        const io::CsvTable h = io::readCsv(dir / "history.csv");
        const auto col = std::find(h.header.begin(), h.header.end(), study_.condition + "_rx_N") - h.header.begin();
        if (static_cast<std::size_t>(col) >= h.header.size()) throw std::runtime_error("no column " + study_.condition + "_rx_N");
        std::vector<double> t, reaction;
        for (const auto& row : h.rows) t.push_back(row[0]), reaction.push_back(row[static_cast<std::size_t>(col)]);
        const SquareWave w = measureSquareWave(t, reaction, cf.amplitude);
        setMetric(r, "period", relative(w.period, cf.period));
        setMetric(r, "amplitude", relative(w.amplitude, cf.amplitude));
        if (w.crossings == 0) r.message = "no sign change of the reaction: end_time shorter than half a period?";
      } catch (const std::exception& e) {
        r.message = std::string("history.csv: ") + e.what();
      }
      return;
    }
    LoadCurve curve;
    if (!study_.condition.empty()) {
      try {
        const io::CsvTable h = io::readCsv(dir / "history.csv");
        out.peakReaction = peakReaction(h, study_.condition);
        curve = loadCurve(h, study_.condition);
      } catch (const std::exception& e) {
        r.message = std::string("history.csv: ") + e.what();
      }
    }
    if (p.reference) {
      keepAsReference(out, curve, ref, refJson);
      refJson["run"] = r.id;
      refJson["label"] = r.label;
    }
    if (ref.available) {
      setMetric(r, "peak_load", relative(out.peakLoad, ref.peakLoad));
      setMetric(r, "peak_reaction", relative(out.peakReaction, ref.peakReaction));
      if (!study_.condition.empty()) {  // at equal displacement of the condition
        const auto [mine, theirs] = dissipatedAtEqualDisplacement(curve, ref.curve);
        setMetric(r, "dissipated_energy", relative(mine, theirs));
      } else {
        setMetric(r, "dissipated_energy", relative(out.dissipated, ref.dissipated));
      }
      setMetric(r, "post_peak_curve", postPeakCurveError(curve, ref.curve));
    }
  }

  // The reference's values for the error measures.
  void keepAsReference(const MpmOutcome& out, LoadCurve curve, ReferenceData& ref, nlohmann::json& refJson) const {
    ref.available = true;
    ref.peakLoad = out.peakLoad;
    ref.peakReaction = out.peakReaction;
    ref.dissipated = out.dissipated;
    ref.curve = std::move(curve);
    refJson = {{"peak_load_N", jsonValue(out.peakLoad)}, {"dissipated_energy_Nmm", jsonValue(out.dissipated)}};
    if (!study_.condition.empty()) refJson["peak_reaction_" + study_.condition + "_N"] = jsonValue(out.peakReaction);
  }

 public:
  // ReferenceKind::Scene: the reference scene, run once into DIR/reference (reused by --resume
  // when it completed there before).
  void runReferenceScene(ReferenceData& ref, nlohmann::json& refJson) const {
    const std::filesystem::path dir = io::prepareOutputDir(dir_ / "reference");
    const mpm::Scene scene = mpm::loadSceneFile(study_.referenceScene);
    RunRecord r;
    MpmOutcome out;
    const bool reuse = (options_.resume || options_.collectOnly) && readSummary(dir, r, out) && r.status == "completed";
    if (options_.collectOnly && !reuse) {
      r.status = "failed";
      r.message = "not run: no completed outputs in reference/";
    } else if (!reuse) {
      executeMpm(scene, dir);
      if (!readSummary(dir, r, out)) r.status = "failed";
    }
    refJson = {{"scene", study_.referenceScene.string()}, {"status", r.status}};
    if (r.status != "completed") {
      refJson["error"] = "the reference scene did not complete: no errors (" + r.message + ")";
      return;
    }
    LoadCurve curve;
    if (!study_.condition.empty()) {
      const io::CsvTable h = io::readCsv(dir / "history.csv");
      out.peakReaction = peakReaction(h, study_.condition);
      curve = loadCurve(h, study_.condition);
    }
    keepAsReference(out, std::move(curve), ref, refJson);
    refJson["scene"] = study_.referenceScene.string();
    refJson["directory"] = "reference";
    refJson["wall_time_s"] = jsonValue(r.wallTime);
  }

 private:

  void runPointScene(const PlannedRun& p, const std::filesystem::path& dir, RunRecord& r, ReferenceData& ref,
                     nlohmann::json& refJson) const {
    const driver::PointScene& scene = *p.point;
    driver::PointRun run;
    for (int rep = 0; rep < study_.repeat; ++rep) {
      const auto start = std::chrono::steady_clock::now();
      run = driver::runPoint(scene);
      const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      r.wallTime = std::isnan(r.wallTime) ? wall : std::min(r.wallTime, wall);
    }
    driver::writeHistoryCsv(run, dir / "history.csv");
    io::writeJsonSummary(driver::pointSummaryJson(scene, run), dir / "summary.json");
    r.status = run.completed ? "completed" : "failed";
    r.message = run.failure;
    const int increments = run.history.empty() ? 0 : run.history.back().increment;
    r.steps = increments;
    r.particles = 1;
    r.updatesPerSecond = r.wallTime > 0.0 ? increments / r.wallTime : NAN;
    r.substepped = static_cast<double>(
        std::count_if(run.history.begin(), run.history.end(), [](const driver::HistoryRow& h) { return h.substeps > 1; }));
    if (!run.completed || run.history.empty()) return;
    const double ft = scene.material.tensileStrength > 0.0 ? scene.material.tensileStrength : 1.0;
    const driver::PointSummary sum = driver::summarise(scene, run);
    if (study_.reference == ReferenceKind::UniaxialTension) {
      try {
        const UniaxialReference cf =
            uniaxialTensionClosedForm(scene.material, scene.effectiveSize, run.history.back().strain[0]);
        std::vector<double> x, y;
        for (const driver::HistoryRow& h : run.history) x.push_back(h.strain[0]), y.push_back(h.stress[0]);
        setMetric(r, "stress_path", maxDeviation(cf.strain, cf.stress, x, y) / ft);
        setMetric(r, "dissipation", relative(run.history.back().dissipation, cf.dissipation));
        setMetric(r, "peak_stress", relative(sum.peakStress, cf.peakStress));
        if (refJson.is_null())
          refJson = {{"closed_form", "uniaxial_tension"},
                     {"peak_stress_MPa", cf.peakStress},
                     {"dissipation_per_volume_MPa", cf.dissipation},
                     {"strain_end", run.history.back().strain[0]},
                     {"source", "material/uniaxial_closed_form.hpp"}};
      } catch (const std::invalid_argument& e) {
        r.message = e.what();
      }
      return;
    }
    if (p.reference) {
      ref.available = true;
      ref.point = run;
      ref.pathParameter = strainArcLength(run);
      ref.peakStress = sum.peakStress;
      refJson = {{"run", r.id},
                 {"label", r.label},
                 {"peak_stress_MPa", sum.peakStress},
                 {"dissipation_per_volume_MPa", run.history.back().dissipation}};
    }
    if (!ref.available) return;
    const std::vector<double> s = strainArcLength(run);
    double worst = 0.0;
    for (int c = 0; c < 3; ++c) {
      std::vector<double> refY, y;
      for (const driver::HistoryRow& h : ref.point.history) refY.push_back(h.stress[c]);
      for (const driver::HistoryRow& h : run.history) y.push_back(h.stress[c]);
      worst = std::max(worst, maxDeviation(ref.pathParameter, refY, s, y));
    }
    setMetric(r, "stress_path", worst / ft);
    setMetric(r, "dissipation", relative(run.history.back().dissipation, ref.point.history.back().dissipation));
    setMetric(r, "peak_stress", relative(sum.peakStress, ref.peakStress));
  }
};

}  // namespace

std::string runDirectory(const PlannedRun& r) {
  char id[16];
  std::snprintf(id, sizeof id, "%03d", r.id);
  return std::string("runs/") + id + "-" + sanitize(r.label);
}

StudyResult runStudy(const Study& study, const std::vector<PlannedRun>& plan, const StudyOptions& options) {
  const std::filesystem::path dir = io::prepareOutputDir(options.outputDir);
  std::vector<std::size_t> order(plan.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_partition(order.begin(), order.end(), [&](std::size_t i) { return plan[i].reference; });

  StudyResult result;
  result.runs.resize(plan.size());
  ReferenceData ref;
  Executor executor(study, options, dir);
  nlohmann::json refJson;
  if (study.reference == ReferenceKind::Scene) {
    if (options.progress) std::cerr << "reference scene " << study.referenceScene.string() << "\n";
    executor.runReferenceScene(ref, refJson);
  }
  for (std::size_t n = 0; n < order.size(); ++n) {
    const PlannedRun& p = plan[order[n]];
    RunRecord r = executor.run(p, ref, refJson);
    result.allCompleted = result.allCompleted && r.status == "completed";
    if (options.progress) {
      std::cerr << "[" << n + 1 << "/" << plan.size() << "] run " << p.id << (p.reference ? " (reference)" : "") << " "
                << p.label << ": " << r.status << ", " << shortNumber(r.wallTime) << " s, error " << shortNumber(r.error)
                << (r.reused ? " (reused)" : "") << (r.message.empty() ? "" : " (" + r.message + ")") << "\n";
    }
    result.runs[order[n]] = std::move(r);
  }
  if (!refJson.is_null()) result.reference = refJson;
  if (options.isolate && study.kind == StudyKind::Mpm) result.studyRssMb = parentRssMb();
  if ((study.reference == ReferenceKind::Run || study.reference == ReferenceKind::Scene) && !ref.available &&
      !result.reference.contains("error"))
    result.reference["error"] = "the reference run did not complete: no errors";

  std::vector<double> cost, error;
  for (const RunRecord& r : result.runs) {
    const bool candidate = r.status == "completed" && !(r.reference && study.reference == ReferenceKind::Run);
    cost.push_back(candidate ? r.wallTime : NAN);
    error.push_back(candidate ? r.error : NAN);
  }
  // An ensemble's runs differ by their seed, a sample and not a setting: no run is "better" than
  // another, so no Pareto front is marked among them (ensemble.csv compares the meshes).
  const bool ensemble = study.samples > 0;
  const std::vector<bool> front = ensemble ? std::vector<bool>(result.runs.size(), false) : paretoFront(cost, error);
  for (std::size_t i = 0; i < result.runs.size(); ++i) result.runs[i].pareto = front[i];

  writeTableCsv(study, result, dir / "study.csv");
  nlohmann::json summary = summaryJson(study, result, options);
  if (ensemble) {
    result.ensemble = summary["ensemble"] = writeEnsemble(study, plan, result, dir);
    summary["pareto"] = nullptr;
    summary["pareto_note"] = "an ensemble: its runs differ by their random seed (samples), not by a setting, so no Pareto "
                             "front is marked; ensemble.csv and the ensemble object compare the meshes";
  }
  io::writeJsonSummary(summary, dir / "summary.json");
  if (!ensemble) plotPareto(study, result, dir);
  if (options.table) {
    writeTable(study, result, *options.table);
    *options.table << ensembleTable(result.ensemble);
  }
  return result;
}

}  // namespace ecm::study
