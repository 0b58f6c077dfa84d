#include "calibration/calibration_run.hpp"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "calibration/fracture_energy.hpp"
#include "io/csv_writer.hpp"
#include "io/gnuplot.hpp"
#include "io/json_summary.hpp"
#include "io/material_yaml.hpp"
#include "io/output_error.hpp"
#include "material/smeared_crack.hpp"

namespace ecm::calibration {

namespace {
constexpr int kCurvePoints = 401;
}  // namespace

CalibrationResult runCalibration(const CalibrationPlan& plan) {
  CalibrationResult r;
  r.mode = plan.mode;
  r.law = plan.law;
  r.width = plan.width;
  switch (plan.mode) {
    case CalibrationMode::Forward:
      r.fractureEnergy = fractureEnergy(r.law, r.width);
      r.targetFractureEnergy = r.fractureEnergy;  // G_F is the result: no target, error 0
      break;
    case CalibrationMode::SolveSofteningModulus:
      r.law.softeningModulus = solveSofteningModulus(r.law, plan.fractureEnergy, r.width).softeningModulus;
      break;
    case CalibrationMode::Fit:
      r.fit = fitSoftening(r.law, plan.fractureEnergy, r.width, *plan.target);
      r.law.softeningExponent = r.fit->softeningExponent;
      r.law.softeningModulus = r.fit->softeningModulus;
      r.target = plan.target;
      break;
    case CalibrationMode::CrackBand:
      // The crack band: int_0^1 F dD = G_F / H (throws RegularisationError for H >= H_crit).
      r.law.softeningModulus = regularisedSofteningModulus(r.law, plan.fractureEnergy, r.width);
      break;
  }
  if (plan.mode != CalibrationMode::Forward) {
    r.fractureEnergy = fractureEnergy(r.law, r.width);
    r.targetFractureEnergy = plan.fractureEnergy;
  }
  r.relativeError = (r.fractureEnergy - r.targetFractureEnergy) / r.targetFractureEnergy;
  r.minimumFractureEnergy = minimumFractureEnergy(r.law.youngsModulus, r.law.tensileStrength, r.width);
  r.criticalSize = criticalSmearedSize(r.law.youngsModulus, r.law.tensileStrength, r.fractureEnergy);

  const SofteningCurve curve(r.law, r.width);
  r.peakStress = curve.peakStress();
  r.openingAt50 = curve.openingAtStressFraction(0.5);
  r.openingAt10 = curve.openingAtStressFraction(0.1);
  r.openingAt1 = curve.openingAtStressFraction(0.01);
  double maxOpening = 1.25 * r.openingAt1;
  if (r.target) maxOpening = std::max(maxOpening, r.target->opening.back());
  r.curve = curve.sample(maxOpening, kCurvePoints);
  return r;
}

nlohmann::json summaryJson(const CalibrationResult& r) {
  nlohmann::json j;
  j["mode"] = toString(r.mode);
  j["E"] = r.law.youngsModulus;
  j["ft"] = r.law.tensileStrength;
  j["Ep"] = r.law.softeningModulus;
  j["n"] = r.law.softeningExponent;
  j["width"] = r.width;
  j["width_is"] = r.mode == CalibrationMode::CrackBand ? "element_size_H" : "band_width_h";
  j["GF"] = r.fractureEnergy;
  j["GF_target"] = r.targetFractureEnergy;
  j["GF_rel_error"] = r.relativeError;
  j["GF_min"] = r.minimumFractureEnergy;
  j["peak_stress"] = r.peakStress;
  j["H_crit"] = r.criticalSize;
  j["w_at_50pct_ft"] = r.openingAt50;
  j["w_at_10pct_ft"] = r.openingAt10;
  j["w_at_1pct_ft"] = r.openingAt1;
  if (r.fit) {
    j["fit_residual"] = r.fit->residual;
    j["fit_target"] = r.target ? r.target->source : "";
    j["fit_points"] = r.target ? r.target->opening.size() : 0u;
    j["fit_evaluations"] = r.fit->evaluations;
    j["fit_n_at_bound"] = r.fit->atBound;
  }
  return j;
}

namespace {
void row(std::ostream& out, const char* what, const char* symbol, double v, const char* unit) {
  char buf[160];
  std::snprintf(buf, sizeof buf, "  %-34s %-8s %-18.10g %s\n", what, symbol, v, unit);
  out << buf;
}
}  // namespace

void printTable(const CalibrationResult& r, std::ostream& out) {
  out << "ecm-calibrate: " << toString(r.mode) << "\n";
  const bool band = r.mode != CalibrationMode::CrackBand;
  row(out, "Young's modulus", "E", r.law.youngsModulus, "MPa");
  row(out, "tensile strength", "ft", r.law.tensileStrength, "MPa");
  row(out, band ? "band width" : "element size (crack band)", band ? "h" : "H", r.width, "mm");
  row(out, "softening exponent", "n", r.law.softeningExponent, "-");
  row(out, "softening modulus", "Ep", r.law.softeningModulus, "MPa");
  row(out, "fracture energy (width * int F dD)", "GF", r.fractureEnergy, "N/mm");
  if (r.mode != CalibrationMode::Forward) {
    row(out, "GF, target", "", r.targetFractureEnergy, "N/mm");
    row(out, "GF relative error", "", r.relativeError, "-");
  }
  row(out, "elastic minimum width*ft^2/(2E)", "GF_min", r.minimumFractureEnergy, "N/mm");
  row(out, "peak stress", "", r.peakStress, "MPa");
  row(out, "critical crack-band size 2EGF/ft^2", "H_crit", r.criticalSize, "mm");
  row(out, "opening at 50% of ft", "w50", r.openingAt50, "mm");
  row(out, "opening at 10% of ft", "w10", r.openingAt10, "mm");
  row(out, "opening at 1% of ft", "w1", r.openingAt1, "mm");
  if (r.fit) {
    row(out, "fit residual RMS((model-target)/ft)", "", r.fit->residual, "-");
    row(out, "fit evaluations (E_p solves)", "", r.fit->evaluations, "");
    if (r.fit->atBound) out << "  warning: the best n lies at the edge of the scanned interval\n";
  }
}

bool writeOutputs(const CalibrationResult& r, const std::filesystem::path& dir) {
  io::writeJsonSummary(summaryJson(r), dir / "summary.json");
  {
    io::CsvWriter csv(dir / "softening.csv", {"w", "sigma", "D", "eps_L"});
    for (const SofteningPoint& p : r.curve) csv.row({p.opening, p.stress, p.damage, p.bandStrain});
    csv.close();
  }
  io::PlotSpec plot;
  std::ostringstream title;
  title.precision(5);
  title << "ecm-calibrate (" << toString(r.mode) << "): E_p = " << r.law.softeningModulus
        << " MPa, n = " << r.law.softeningExponent << ", G_F = " << r.fractureEnergy << " N/mm";
  plot.title = title.str();
  plot.xLabel = "opening w (mm)";
  plot.yLabel = "stress {/Symbol s} (MPa)";
  plot.enhancedLabels = true;  // the sigma of the y label
  plot.series.push_back({"softening.csv", "1:2", "", "model, Eq. (13)", "lines lw 2"});
  if (r.target) {
    io::CsvWriter csv(dir / "target.csv", {"w", "sigma"});
    for (std::size_t i = 0; i < r.target->opening.size(); ++i) csv.row({r.target->opening[i], r.target->stress[i]});
    csv.close();
    if (r.target->source == "hordijk") {
      plot.functions.push_back("hordijk(x) = " + hordijkGnuplot(r.law.tensileStrength, r.targetFractureEnergy));
      plot.series.push_back({"", "", "hordijk(x)", "Hordijk (Cornelissen et al. 1986)", "lines dt 2 lw 2"});
    } else {
      plot.series.push_back({"target.csv", "1:2", "", "target points", "points pt 7 ps 0.8"});
    }
  }
  return io::renderPlot(plot, dir / "softening.png");
}

MaterialParams calibratedMaterial(const CalibrationResult& r, const CalibrationPlan& plan) {
  MaterialParams m;
  m.name = plan.name;
  m.elastic = {r.law.youngsModulus, plan.poissonRatio, plan.hypothesis};
  m.density = plan.density;
  m.tensileStrength = r.law.tensileStrength;
  m.softeningModulus = r.law.softeningModulus;
  m.softeningExponent = r.law.softeningExponent;
  m.fractureEnergy = r.targetFractureEnergy;  // the G_F asked for (forward: the computed one)
  if (r.mode == CalibrationMode::CrackBand) {
    m.model = ModelKind::SmearedCrack;
  } else {
    m.model = ModelKind::Enriched;
    m.bandWidth = r.width;
  }
  return m;
}

void writeRequestedFiles(const CalibrationResult& r, const CalibrationPlan& plan, std::ostream& log) {
  if (plan.writeMaterial) {
    io::writeMaterialFile(calibratedMaterial(r, plan), *plan.writeMaterial);
    log << "  material written to " << plan.writeMaterial->string() << "\n";
  }
  if (plan.writeUmat) {
    umat::CardRequest card;
    card.name = plan.name;
    card.effectiveSizes = plan.elementSizes;
    card.dialect = plan.dialect;
    card.source = "calibrated by ecm-calibrate (" + std::string(toString(r.mode)) + ")";
    const std::string text = umat::materialCard(calibratedMaterial(r, plan), card);
    std::ofstream out(*plan.writeUmat);
    out << text;
    out.close();
    if (!out) throw io::OutputError(*plan.writeUmat, "the UMAT card could not be written");
    log << "  UMAT card written to " << plan.writeUmat->string() << " (" << plan.elementSizes.size()
        << (plan.elementSizes.size() == 1 ? " material" : " materials, one per element size") << ")\n";
  }
}

}  // namespace ecm::calibration
