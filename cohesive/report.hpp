#pragma once
// The outputs of an ecm-cohesive run: history.csv (written step by step, so that a failed run
// keeps what converged), ligament.csv, summary.json and the P-control plot.
#include <filesystem>
#include <memory>
#include <optional>

#include <nlohmann/json.hpp>

#include "cohesive/scene.hpp"
#include "cohesive/solver.hpp"
#include "io/csv_writer.hpp"

namespace ecm::cohesive {

class HistoryWriter {
 public:
  HistoryWriter(const std::filesystem::path& path, const HalfModel& model);
  void write(const StepRecord& r);  // one row, flushed
 private:
  io::CsvWriter csv_;
};

// P at a control value, linearly between steps; nullopt beyond the last step. When the control
// passes the value more than once the first crossing counts.
std::optional<double> loadAt(const std::vector<StepRecord>& history, double control);

struct RunInfo {
  double wallSeconds = 0.0;
  bool completed = true;
  std::string failure;
};

nlohmann::json runSummary(const Scene& scene, const HalfModel& model, const SolveResult& result, const RunInfo& info);
void writeLigament(const std::filesystem::path& path, const SolveResult& result);
// P against the control (history.csv); a missing gnuplot only warns.
void plotLoadCurve(const std::filesystem::path& dir, const Scene& scene, const HalfModel& model);

}  // namespace ecm::cohesive
