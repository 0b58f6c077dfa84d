// ecm-study: the Pareto marking and the outputs of a study: study.csv, summary.json,
// pareto.png (with pareto_runs.csv, pareto_front.csv) and the table on the terminal.
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "io/atomic_file.hpp"
#include "io/gnuplot.hpp"
#include "study/study.hpp"
#include "study/internal.hpp"

namespace ecm::study {

using namespace detail;

std::vector<bool> paretoFront(const std::vector<double>& cost, const std::vector<double>& error) {
  const std::size_t n = std::min(cost.size(), error.size());
  std::vector<bool> front(cost.size(), false);
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(cost[i]) || !std::isfinite(error[i])) continue;
    bool dominated = false;
    for (std::size_t j = 0; j < n && !dominated; ++j)
      dominated = j != i && std::isfinite(cost[j]) && std::isfinite(error[j]) && cost[j] <= cost[i] &&
                  error[j] <= error[i] && (cost[j] < cost[i] || error[j] < error[i]);
    front[i] = !dominated;
  }
  return front;
}

// ---------------------------------------------------------------------------------------------
// Outputs

namespace {

std::string csvField(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (const char c : s) q += c == '"' ? std::string("\"\"") : (c == '\n' ? std::string(" ") : std::string(1, c));
  return q + "\"";
}

std::string csvNumber(double v) { return std::isfinite(v) ? numberText(v) : ""; }

void cell(std::string& text, const std::string& field) {
  text += ',';
  text += field;
}

}  // namespace

namespace detail {

nlohmann::json jsonValue(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(); }

std::string shortNumber(double v, int precision) {
  if (!std::isfinite(v)) return "-";
  std::ostringstream s;
  s << std::setprecision(precision) << v;
  return s.str();
}

void writeTableCsv(const Study& study, const StudyResult& result, const std::filesystem::path& path) {
  std::string text = "id,label";
  for (const Knob& k : study.knobs) text += "," + csvField(k.key);
  text += ",reference,status,wall_time_s,cpu_time_s,steps,particles,updates_per_s,bytes_per_particle,peak_rss_mb,substepped";
  for (const std::string& m : study.metrics) text += "," + m + "_error";
  text += ",error,pareto,directory,message\n";
  for (const RunRecord& r : result.runs) {
    text += std::to_string(r.id) + "," + csvField(r.label);
    for (const std::string& v : r.values) cell(text, csvField(v));
    text += std::string(",") + (r.reference ? "1" : "0") + "," + r.status;
    for (const double v : {r.wallTime, r.cpuTime, r.steps, r.particles, r.updatesPerSecond, r.bytesPerParticle, r.peakRssMb, r.substepped})
      cell(text, csvNumber(v));
    for (const double m : r.metrics) cell(text, csvNumber(m));
    text += "," + csvNumber(r.error) + "," + (r.pareto ? "1" : "0") + "," + csvField(r.directory) + "," + csvField(r.message) + "\n";
  }
  io::writeFileAtomically(path, text);
}

void writeTable(const Study& study, const StudyResult& result, std::ostream& out) {
  std::vector<std::string> header{"id"};
  for (const Knob& k : study.knobs) header.push_back(k.key);
  for (const char* h : {"status", "time_s", "cpu_s", "steps", "particles", "B/particle", "rss_MB"}) header.push_back(h);
  for (const std::string& m : study.metrics) header.push_back(m);
  header.push_back("error");
  const bool ensemble = study.samples > 0;  // no Pareto front among samples
  if (!ensemble) header.push_back("pareto");
  std::vector<std::vector<std::string>> rows;
  for (const RunRecord& r : result.runs) {
    std::vector<std::string> row{std::to_string(r.id) + (r.reference ? "R" : "")};
    for (const std::string& v : r.values) row.push_back(v);
    row.push_back(r.status);
    row.push_back(shortNumber(r.wallTime));
    row.push_back(shortNumber(r.cpuTime));
    row.push_back(shortNumber(r.steps, 6));
    row.push_back(shortNumber(r.particles, 7));
    row.push_back(shortNumber(r.bytesPerParticle, 4));
    row.push_back(shortNumber(r.peakRssMb, 3));
    for (const double m : r.metrics) row.push_back(shortNumber(m, 3));
    row.push_back(shortNumber(r.error, 3));
    if (!ensemble) row.push_back(r.pareto ? "*" : "");
    rows.push_back(std::move(row));
  }
  std::vector<std::size_t> width(header.size(), 0);
  for (std::size_t c = 0; c < header.size(); ++c) {
    width[c] = header[c].size();
    for (const auto& row : rows) width[c] = std::max(width[c], row[c].size());
  }
  auto line = [&](const std::vector<std::string>& cells) {
    for (std::size_t c = 0; c < cells.size(); ++c) out << (c ? "  " : "") << std::setw(static_cast<int>(width[c])) << cells[c];
    out << "\n";
  };
  line(header);
  for (const auto& row : rows) line(row);
}

void plotPareto(const Study& study, const StudyResult& result, const std::filesystem::path& dir) {
  std::string all = "wall_time_s,error,id\n", front = all;
  std::vector<const RunRecord*> onFront;
  int points = 0;
  for (const RunRecord& r : result.runs) {
    if (!(r.wallTime > 0.0) || !std::isfinite(r.error) || (r.reference && study.reference == ReferenceKind::Run)) continue;
    const double e = std::max(r.error, 1e-16);  // log axis: an exact result is drawn at 1e-16
    all += numberText(r.wallTime) + "," + numberText(e) + "," + std::to_string(r.id) + "\n";
    ++points;
    if (r.pareto) onFront.push_back(&r);
  }
  std::sort(onFront.begin(), onFront.end(), [](const RunRecord* a, const RunRecord* b) { return a->wallTime < b->wallTime; });
  for (const RunRecord* r : onFront)
    front += numberText(r->wallTime) + "," + numberText(std::max(r->error, 1e-16)) + "," + std::to_string(r->id) + "\n";
  io::writeFileAtomically(dir / "pareto_runs.csv", all);
  io::writeFileAtomically(dir / "pareto_front.csv", front);
  if (points == 0) return;
  io::PlotSpec spec;
  spec.title = study.name + ": error against wall time (labels: run id; line: the non-dominated settings)";
  spec.xLabel = "wall time (s)";
  std::string metrics;
  for (std::string m : study.metrics) {  // gnuplot's enhanced text would read '_' as a subscript
    std::replace(m.begin(), m.end(), '_', ' ');
    metrics += (metrics.empty() ? "" : ", ") + m;
  }
  spec.yLabel = "error: max |" + metrics + "|";
  spec.logX = spec.logY = true;
  spec.series.push_back({"pareto_runs.csv", "1:2", "", "runs", "points pt 7 ps 1 lc rgb '#808080'"});
  spec.series.push_back({"pareto_front.csv", "1:2", "", "non-dominated", "linespoints pt 7 ps 1.6 lw 2 lc rgb '#d62728'"});
  // Every run's id while they are few; only the front's when a grid of runs would bury them.
  spec.series.push_back({points <= 40 ? "pareto_runs.csv" : "pareto_front.csv", "1:2:3", "", "",
                         "labels offset char 0.9,0.6 font ',8' tc rgb '#303030'"});
  io::renderPlot(spec, dir / "pareto.png");
}

nlohmann::json summaryJson(const Study& study, const StudyResult& result, const StudyOptions& options) {
  nlohmann::json knobs = nlohmann::json::array();
  for (const Knob& k : study.knobs) {
    nlohmann::json values = nlohmann::json::array();
    for (const auto& v : k.values) values.push_back(valueText(v));
    knobs.push_back({{"key", k.key}, {"values", values}});
  }
  nlohmann::json runs = nlohmann::json::array(), pareto = nlohmann::json::array();
  for (const RunRecord& r : result.runs) {
    nlohmann::json values, metrics;
    for (std::size_t k = 0; k < study.knobs.size(); ++k) values[study.knobs[k].key] = r.values[k];
    for (std::size_t m = 0; m < study.metrics.size(); ++m) metrics[study.metrics[m]] = jsonValue(r.metrics[m]);
    runs.push_back({{"id", r.id},
                    {"label", r.label},
                    {"values", values},
                    {"reference", r.reference},
                    {"status", r.status},
                    {"message", r.message},
                    {"directory", r.directory},
                    {"wall_time_s", jsonValue(r.wallTime)},
                    {"cpu_time_s", jsonValue(r.cpuTime)},
                    {"steps", jsonValue(r.steps)},
                    {"particles", jsonValue(r.particles)},
                    {"updates_per_s", jsonValue(r.updatesPerSecond)},
                    {"bytes_per_particle", jsonValue(r.bytesPerParticle)},
                    {"peak_rss_mb", jsonValue(r.peakRssMb)},
                    {"substepped", jsonValue(r.substepped)},
                    {"errors", metrics},
                    {"error", jsonValue(r.error)},
                    {"pareto", r.pareto},
                    {"reused", r.reused}});
    if (r.pareto) pareto.push_back(r.id);
  }
  return {{"study", study.name},
          {"file", study.file},
          {"kind", study.kind == StudyKind::Mpm ? "mpm" : "point"},
          {"base_scene", study.scene.string()},
          {"design", study.design == StudyDesign::Grid ? "grid" : "one_at_a_time"},
          {"threads", study.kind == StudyKind::Mpm ? nlohmann::json(options.threads) : nlohmann::json()},
          {"isolated_runs", study.kind == StudyKind::Mpm && options.isolate},
          {"study_process_rss_mb", jsonValue(result.studyRssMb)},
          {"repeat", study.repeat},
          {"knobs", knobs},
          {"metrics", study.metrics},
          {"reference", result.reference},
          {"runs", runs},
          {"pareto", pareto},
          {"all_completed", result.allCompleted},
          {"notes",
           "errors are signed relative errors (stress_path: max deviation / f_t'); error = max |error| of the metrics; "
           "wall times are the shortest of `repeat` runs on a machine shared with other work (noisy; cpu_time_s, the run "
           "process's user + system time, is less sensitive to other work); peak_rss_mb is "
           "the peak resident memory of the run's own process (isolated mpm runs only; it includes the pages shared with the study process, study_process_rss_mb); bytes_per_particle counts the "
           "solver's particle arrays at the end of the run, cracked points' band states included"},
          {"units", "mm, N, MPa, t, s"}};
}

}  // namespace detail

std::string notCompletedList(const StudyResult& result) {
  std::string list;
  std::size_t count = 0;
  for (const RunRecord& r : result.runs) {
    if (r.status == "completed") continue;
    ++count;
    list.append("  run ").append(std::to_string(r.id)).append(r.reference ? " (reference)" : "").append(": ").append(r.status);
    if (!r.message.empty()) list.append(" (").append(r.message).append(")");
    list.append("\n");
  }
  if (count == 0) return "";
  return std::to_string(count) + " of " + std::to_string(result.runs.size()) + " runs did not complete:\n" + list;
}

}  // namespace ecm::study
