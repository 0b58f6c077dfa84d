#pragma once
// Internal to ecm-study (study/*.cpp), not part of study.hpp: the helpers its files share.
#include <cstddef>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "study/study.hpp"

namespace ecm::study::detail {

// --- knobs.cpp: values as text, key paths ---

// Shortest round-trip text of a number.
std::string numberText(double v);
// A finite number (a leading '+' allowed), or nothing.
std::optional<double> parseNumber(const std::string& s);
// A value as text: scalars as written, sequences and maps in flow style.
std::string valueText(const YAML::Node& n);

// Key paths: "a.b[0].c"
struct PathStep {
  std::string key;
  std::vector<std::size_t> indices;
};

// Throws std::invalid_argument for a malformed path.
std::vector<PathStep> parsePath(const std::string& path);

// --- plan.cpp ---

// A whole file as text; io::InputError if it cannot be opened.
std::string readText(const std::filesystem::path& path);

// --- report.cpp: the outputs ---

nlohmann::json jsonValue(double v);  // null for a non-finite number
std::string shortNumber(double v, int precision = 3);  // "-" for a non-finite number
void writeTableCsv(const Study& study, const StudyResult& result, const std::filesystem::path& path);
void writeTable(const Study& study, const StudyResult& result, std::ostream& out);
void plotPareto(const Study& study, const StudyResult& result, const std::filesystem::path& dir);
nlohmann::json summaryJson(const Study& study, const StudyResult& result, const StudyOptions& options);

// --- ensemble.cpp: samples: N ---

// Writes ensemble_samples.csv, ensemble.csv, ensemble_histogram.png and weibull.png into dir
// from the runs' folders (result.runs in plan order); returns summary.json's "ensemble".
nlohmann::json writeEnsemble(const Study& study, const std::vector<PlannedRun>& plan, const StudyResult& result,
                             const std::filesystem::path& dir);

}  // namespace ecm::study::detail
