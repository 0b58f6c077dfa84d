#pragma once
// Carrying out a calibration plan and reporting it: the stdout table, summary.json,
// softening.csv (w, sigma, D, eps_L), target.csv when fitting, softening.png, and the
// calibrated material as a material YAML file.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <ostream>
#include <vector>

#include "calibration/calibration_input.hpp"
#include "calibration/softening_curve.hpp"
#include "calibration/softening_fit.hpp"
#include "material/material.hpp"

namespace ecm::calibration {

struct CalibrationResult {
  CalibrationMode mode = CalibrationMode::SolveSofteningModulus;
  DamageLawParams law;                // the calibrated (or given) law: E, f_t', E_p, n
  double width = 0.0;                 // h, or H for the crack band (mm)
  double fractureEnergy = 0.0;        // width * int_0^1 F dD of the law (N/mm)
  double targetFractureEnergy = 0.0;  // the G_F asked for (= fractureEnergy in forward mode)
  double relativeError = 0.0;         // (fractureEnergy - targetFractureEnergy) / targetFractureEnergy, 0 forward
  double minimumFractureEnergy = 0.0; // width f_t'^2 / (2E)
  double peakStress = 0.0;            // MPa
  double criticalSize = 0.0;          // H_crit = 2 E G_F / f_t'^2 (mm)
  double openingAt50 = 0.0, openingAt10 = 0.0, openingAt1 = 0.0;  // w at 50%, 10%, 1% of f_t' (mm)
  std::optional<FitResult> fit;
  std::optional<TargetCurve> target;
  std::vector<SofteningPoint> curve;  // for softening.csv
};

// Throws RegularisationError (material library) for a crack band with H >= H_crit.
CalibrationResult runCalibration(const CalibrationPlan& plan);

nlohmann::json summaryJson(const CalibrationResult& r);
void printTable(const CalibrationResult& r, std::ostream& out);
// summary.json, softening.csv, target.csv (fit), softening.png (+ .gp) in `dir` (prepared by the
// caller). Returns false when only the plot could not be made.
bool writeOutputs(const CalibrationResult& r, const std::filesystem::path& dir);
// The calibrated law as a material: enriched (band width h) or, for the crack band,
// smeared_crack with the regularised E_p and G_F.
MaterialParams calibratedMaterial(const CalibrationResult& r, const CalibrationPlan& plan);
// The files the plan asks for beyond the outputs: the material YAML (--write-material) and ecm's
// UMAT card (--write-umat, one *MATERIAL per element size); one line per file written on `log`.
// Throws io::OutputError naming a file that cannot be written.
void writeRequestedFiles(const CalibrationResult& r, const CalibrationPlan& plan, std::ostream& log);

}  // namespace ecm::calibration
