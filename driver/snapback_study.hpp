#pragma once
// The snap-back study: one material, a sweep of effective sizes H, the enriched point (strain
// control and opening control) and the regularised smeared crack at every H. Shows that the
// enriched point keeps one traction-opening curve and dissipates G_F at every H, snapping back
// (as a bar with a cohesive crack would) beyond h (E + E_p)/E_p, while the smeared crack's curve
// changes with H and has no regularisation beyond H_crit = 2 E G_F / f_t'^2.
#include <filesystem>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "driver/point_driver.hpp"

namespace ecm::io {
class YamlMap;
}

namespace ecm::driver {

struct SnapBackStudy {
  std::string name = "snapback-study";
  MaterialParams material;            // enriched; fracture_energy is the smeared target
  std::vector<double> effectiveSizes; // H (mm)
  int strainIncrements = 600;         // strain-control runs: 0 -> f_t'/E + opening/H
  double opening = 0.5;               // opening-control runs: up to this [u].n (mm)
  int openingIncrements = 1000;
};

struct StudyRow {
  double effectiveSize = 0.0;
  // enriched, strain control
  bool strainControlSnapBack = false;
  int snapBackIncrement = -1;
  double snapBackStressDrop = 0.0;
  // enriched, opening control
  double peakStress = 0.0;
  double energyRatio = 0.0;            // H x dissipation / G_F
  bool macroSnapsBack = false;         // the traced macro strain decreases somewhere
  double closedFormStressError = 0.0;  // max |sigma - sigma_cf(x)| / f_t'
  double closedFormStrainError = 0.0;  // max |eps - eps_cf(x)| / (f_t'/E)
  double tractionOpeningError = 0.0;   // max |t(w) - t_ref(w)| / f_t' against the first H
  bool enrichedCompleted = false;
  // smeared crack
  bool smearedRegularised = false;
  double smearedSofteningModulus = 0.0;
  double smearedPeakStress = 0.0;
  double smearedEnergyRatio = 0.0;
  double smearedTractionOpeningError = 0.0;  // against the enriched band curve
  double criticalSize = 0.0;                 // H_crit
  double requiredStrength = 0.0;             // sqrt(2 E G_F / H) when H >= H_crit
  std::string smearedNote;
};

struct SnapBackStudyResult {
  std::vector<StudyRow> rows;
  double snapBackSize1D = 0.0;  // h (E + E_p) / E_p
  double snapBackSize = 0.0;    // E / max(-d sigma / d w) of the band's actual curve (nu included)
  double criticalSize = 0.0;    // 2 E G_F / f_t'^2
  bool allRunsCompleted = true;
};

SnapBackStudy loadSnapBackStudy(const std::filesystem::path& file);
// The same from a map already parsed (the Python module's dicts).
SnapBackStudy readSnapBackStudy(const io::YamlMap& map);
SnapBackStudyResult runSnapBackStudy(const SnapBackStudy& study, const std::filesystem::path& dir, std::ostream& table);

}  // namespace ecm::driver
