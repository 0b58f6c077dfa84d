#include "driver/snapback_study.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "driver/point_output.hpp"
#include "io/csv_writer.hpp"
#include "io/gnuplot.hpp"
#include "io/json_summary.hpp"
#include "io/material_yaml.hpp"
#include "io/output_dir.hpp"
#include "io/yaml_input.hpp"
#include "material/uniaxial_closed_form.hpp"

namespace ecm::driver {

namespace {

using Curve = std::vector<std::pair<double, double>>;  // (opening w, normal traction), w increasing

// Interpolated traction at opening w, or nullopt outside the curve.
std::optional<double> tractionAt(const Curve& c, double w) {
  for (size_t i = 1; i < c.size(); ++i) {
    if (c[i - 1].first <= w && w <= c[i].first && c[i].first > c[i - 1].first) {
      const double s = (w - c[i - 1].first) / (c[i].first - c[i - 1].first);
      return c[i - 1].second + s * (c[i].second - c[i - 1].second);
    }
  }
  return std::nullopt;
}

double maxDeviation(const Curve& curve, const Curve& reference) {
  double worst = 0.0;
  for (const auto& [w, t] : curve)
    if (const auto r = tractionAt(reference, w)) worst = std::max(worst, std::abs(t - *r));
  return worst;
}

Curve openingCurve(const PointRun& run) {
  Curve c;
  for (const HistoryRow& r : run.history)
    if (r.damage > 0.0 && (c.empty() || r.opening > c.back().first)) c.emplace_back(r.opening, normalTraction(r));
  return c;
}

std::string tag(double h) {
  std::ostringstream s;
  s << h;
  return s.str();
}

PointScene uniaxialScene(const MaterialParams& m, double bigH, double strain, int increments, double opening,
                         int openingIncrements) {
  PointScene s;
  s.material = m;
  s.effectiveSize = bigH;
  PresetPath p;
  p.name = "uniaxial_tension";
  p.strain = strain;
  p.increments = increments;
  p.opening = opening;
  s.path = presetSegments(p, m.elastic.poissonRatio);
  if (opening > 0.0) {
    s.path.back().increments = openingIncrements;
    s.path.back().firstOpeningIncrement = 1e-7 * opening;  // resolve the peak, then stride out
  }
  return s;
}

// E / max(-d sigma/d w) over the band's traction-opening curve (closed form, nu included).
double snapBackSize(const MaterialParams& m) {
  const DamageLawParams law = m.band().law();
  return snapBackEffectiveSize(
      [&](double x) { return uniaxialBandResponse(law, m.elastic.poissonRatio, m.bandWidth, x); }, m.elastic.youngsModulus);
}

}  // namespace

SnapBackStudy loadSnapBackStudy(const std::filesystem::path& file) { return readSnapBackStudy(io::loadYamlFile(file)); }

SnapBackStudy readSnapBackStudy(const io::YamlMap& map) {
  SnapBackStudy s;
  s.name = map.getOr<std::string>("name", "snapback-study");
  s.material = io::readMaterial(map.child("material"));
  if (s.material.model != ModelKind::Enriched) map.fail("material", "the study needs an enriched material");
  if (!(s.material.fractureEnergy > 0.0))
    map.fail("material", "the material needs fracture_energy (N/mm): the smeared crack is regularised to it");
  s.effectiveSizes = map.getVector("effective_sizes", 0, io::Range::positive());
  for (double size : s.effectiveSizes)
    if (const std::string problem = effectiveSizeProblem(size, s.material.bandWidth, s.material.secondBand == SecondBandOption::Off ? 1 : 2); !problem.empty())
      map.fail("effective_sizes", problem);
  s.strainIncrements = map.getOr<int>("strain_increments", 600, io::Range{10.0, 1e7, true, true});
  s.opening = map.getOr<double>("opening", 0.5, io::Range::positive());
  s.openingIncrements = map.getOr<int>("opening_increments", 1000, io::Range{10.0, 1e7, true, true});
  map.finish();
  return s;
}

SnapBackStudyResult runSnapBackStudy(const SnapBackStudy& study, const std::filesystem::path& dir, std::ostream& out) {
  const MaterialParams& m = study.material;
  const double e = m.elastic.youngsModulus, ft = m.tensileStrength, gf = m.fractureEnergy;
  const DamageLawParams law = m.band().law();
  SnapBackStudyResult result;
  result.snapBackSize1D = m.bandWidth * (e + m.softeningModulus) / m.softeningModulus;
  result.snapBackSize = snapBackSize(m);
  result.criticalSize = criticalSmearedSize(e, ft, gf);
  Curve reference;
  std::vector<std::string> enrichedDirs, smearedDirs;
  for (double bigH : study.effectiveSizes) {
    StudyRow row;
    row.effectiveSize = bigH;
    row.criticalSize = result.criticalSize;
    const double strainEnd = ft / e + study.opening / bigH;
    // Enriched, strain control: is the snap-back detected?
    const PointScene strainScene = uniaxialScene(m, bigH, strainEnd, study.strainIncrements, 0.0, 0);
    const PointRun strainRun = runPoint(strainScene);
    writePointOutputs(strainScene, strainRun, io::prepareOutputDir(dir / ("enriched-strain-H" + tag(bigH))));
    row.strainControlSnapBack = strainRun.snapBack.detected;
    row.snapBackIncrement = strainRun.snapBack.increment;
    if (strainRun.snapBack.jumped) row.snapBackStressDrop = strainRun.snapBack.stressBefore - strainRun.snapBack.stressAfter;
    // Enriched, opening control: the whole branch.
    const PointScene openScene = uniaxialScene(m, bigH, 0.5 * ft / e, 10, study.opening, study.openingIncrements);
    const PointRun openRun = runPoint(openScene);
    const std::string openDir = "enriched-opening-H" + tag(bigH);
    writePointOutputs(openScene, openRun, io::prepareOutputDir(dir / openDir));
    enrichedDirs.push_back(openDir);
    row.enrichedCompleted = strainRun.completed && openRun.completed;
    result.allRunsCompleted = result.allRunsCompleted && row.enrichedCompleted;
    const PointSummary sum = summarise(openScene, openRun);
    row.peakStress = sum.peakStress;
    row.energyRatio = sum.energyPerArea / gf;
    double previousStrain = -INFINITY;
    for (const HistoryRow& r : openRun.history) {
      if (r.openingControl && r.strain[0] < previousStrain - 1e-15) row.macroSnapsBack = true;
      previousStrain = r.strain[0];
      if (r.damage <= 0.0) continue;
      const UniaxialBandPoint cf = uniaxialBandResponse(law, m.elastic.poissonRatio, m.bandWidth, r.integrity);
      row.closedFormStressError = std::max(row.closedFormStressError, std::abs(r.stress[0] - cf.stress) / ft);
      row.closedFormStrainError =
          std::max(row.closedFormStrainError, std::abs(r.strain[0] - uniaxialMacroStrain(cf, e, bigH)) / (ft / e));
    }
    const Curve curve = openingCurve(openRun);
    if (reference.empty()) reference = curve;
    row.tractionOpeningError = maxDeviation(curve, reference) / ft;
    // Smeared crack, regularised for this H (crack band), strain control.
    MaterialParams smeared = m;
    smeared.model = ModelKind::SmearedCrack;
    smeared.regularisedForSize = bigH;
    try {
      const PointScene ss = uniaxialScene(smeared, bigH, strainEnd, 4 * study.strainIncrements, 0.0, 0);
      const PointRun sr = runPoint(ss);
      const std::string sdir = "smeared-H" + tag(bigH);
      writePointOutputs(ss, sr, io::prepareOutputDir(dir / sdir));
      smearedDirs.push_back(sdir);
      row.smearedRegularised = true;
      row.smearedSofteningModulus = Material(smeared).params().softeningModulus;
      const PointSummary s2 = summarise(ss, sr);
      row.smearedPeakStress = s2.peakStress;
      row.smearedEnergyRatio = s2.energyPerArea / gf;
      row.smearedTractionOpeningError = maxDeviation(openingCurve(sr), reference) / ft;
      result.allRunsCompleted = result.allRunsCompleted && sr.completed;
    } catch (const RegularisationError& err) {
      row.requiredStrength = err.requiredStrength;
      row.smearedNote = err.what();
    }
    result.rows.push_back(row);
  }

  // Table (stdout and CSV), summary.json, plots.
  out << "snap-back study: " << m.name << " (E = " << e << " MPa, nu = " << m.elastic.poissonRatio << ", f_t' = " << ft
      << " MPa, E_p = " << m.softeningModulus << " MPa, n = " << m.softeningExponent << ", h = " << m.bandWidth
      << " mm, G_F = " << gf << " N/mm)\n";
  out << "snap-back size h (E + E_p)/E_p = " << result.snapBackSize1D << " mm (1D); of the band's actual curve "
      << result.snapBackSize << " mm; smeared H_crit = 2 E G_F / f_t'^2 = " << result.criticalSize << " mm\n";
  out << std::setw(8) << "H(mm)" << std::setw(10) << "peak" << std::setw(9) << "HW/G_F" << std::setw(7) << "snaps"
      << std::setw(8) << "detect" << std::setw(9) << "drop" << std::setw(10) << "cf_sig" << std::setw(10) << "t(w)dev"
      << " | " << std::setw(10) << "Ep_smear" << std::setw(9) << "peak" << std::setw(9) << "HW/G_F" << std::setw(10)
      << "t(w)dev" << "\n";
  io::CsvWriter csv(dir / "study.csv",
                    {"H", "peak_stress", "energy_ratio", "macro_snaps_back", "strain_control_snapback",
                     "snapback_increment", "stress_drop", "closed_form_stress_error", "closed_form_strain_error",
                     "traction_opening_error", "smeared_regularised", "smeared_Ep", "smeared_peak_stress",
                     "smeared_energy_ratio", "smeared_traction_opening_error", "required_strength"});
  nlohmann::json rows = nlohmann::json::array();
  for (const StudyRow& r : result.rows) {
    out << std::setw(8) << r.effectiveSize << std::setw(10) << std::setprecision(5) << r.peakStress << std::setw(9)
        << std::setprecision(4) << r.energyRatio << std::setw(7) << (r.macroSnapsBack ? "yes" : "no") << std::setw(8)
        << (r.strainControlSnapBack ? "yes" : "no") << std::setw(9) << std::setprecision(3) << r.snapBackStressDrop
        << std::setw(10) << std::setprecision(2) << r.closedFormStressError << std::setw(10) << r.tractionOpeningError
        << " | ";
    if (r.smearedRegularised)
      out << std::setw(10) << std::setprecision(5) << r.smearedSofteningModulus << std::setw(9) << r.smearedPeakStress
          << std::setw(9) << std::setprecision(4) << r.smearedEnergyRatio << std::setw(10) << std::setprecision(2)
          << r.smearedTractionOpeningError << "\n";
    else
      out << "no regularisation: H >= H_crit = " << r.criticalSize << " mm; needs f_t' <= " << r.requiredStrength
          << " MPa\n";
    csv.row({r.effectiveSize, r.peakStress, r.energyRatio, double(r.macroSnapsBack), double(r.strainControlSnapBack),
             double(r.snapBackIncrement), r.snapBackStressDrop, r.closedFormStressError, r.closedFormStrainError,
             r.tractionOpeningError, double(r.smearedRegularised), r.smearedSofteningModulus, r.smearedPeakStress,
             r.smearedEnergyRatio, r.smearedTractionOpeningError, r.requiredStrength});
    nlohmann::json j = {{"H", r.effectiveSize},
                        {"enriched",
                         {{"peak_stress", r.peakStress},
                          {"energy_ratio", r.energyRatio},
                          {"macro_snaps_back", r.macroSnapsBack},
                          {"strain_control_snapback_detected", r.strainControlSnapBack},
                          {"snapback_first_increment", r.snapBackIncrement},
                          {"snapback_stress_drop", r.snapBackStressDrop},
                          {"closed_form_stress_error", r.closedFormStressError},
                          {"closed_form_strain_error", r.closedFormStrainError},
                          {"traction_opening_error", r.tractionOpeningError},
                          {"completed", r.enrichedCompleted}}}};
    if (r.smearedRegularised)
      j["smeared"] = {{"regularised", true},
                      {"Ep", r.smearedSofteningModulus},
                      {"peak_stress", r.smearedPeakStress},
                      {"energy_ratio", r.smearedEnergyRatio},
                      {"traction_opening_error", r.smearedTractionOpeningError}};
    else
      j["smeared"] = {{"regularised", false}, {"H_crit", r.criticalSize}, {"required_strength", r.requiredStrength},
                      {"message", r.smearedNote}};
    rows.push_back(j);
  }
  csv.close();
  double worstTraction = 0.0, worstEnergy = 0.0, worstClosedForm = 0.0;
  for (const StudyRow& r : result.rows) {
    worstTraction = std::max(worstTraction, r.tractionOpeningError);
    worstEnergy = std::max(worstEnergy, std::abs(r.energyRatio - 1.0));
    worstClosedForm = std::max(worstClosedForm, r.closedFormStressError);
  }
  out << "enriched: max traction-opening deviation " << worstTraction << " f_t', max |H W/G_F - 1| = " << worstEnergy
      << ", max closed-form deviation " << worstClosedForm << " f_t'\n";
  io::writeJsonSummary({{"units", "mm, N, MPa; energy ratios are H x dissipation / G_F; deviations in units of f_t'"},
                        {"material", io::materialYaml(m)},
                        {"snapback_size_1d", result.snapBackSize1D},
                        {"snapback_size", result.snapBackSize},
                        {"H_crit", result.criticalSize},
                        {"max_traction_opening_error", worstTraction},
                        {"max_energy_error", worstEnergy},
                        {"max_closed_form_error", worstClosedForm},
                        {"all_runs_completed", result.allRunsCompleted},
                        {"rows", rows}},
                       dir / "summary.json");
  io::PlotSpec to;
  to.title = "traction-opening: enriched (solid) for every H, regularised smeared crack (dashed)";
  to.xLabel = "inelastic opening w (mm)";
  to.yLabel = "normal traction (MPa)";
  to.xRange = "[0:" + std::to_string(std::min(study.opening, 0.3)) + "]";
  for (size_t i = 0; i < enrichedDirs.size(); ++i)
    to.series.push_back({enrichedDirs[i] + "/history.csv", "($9 > 0 ? $13 : 1/0):14", "",
                         "enriched H = " + tag(result.rows[i].effectiveSize) + " mm", "lines lw 2"});
  for (const std::string& d : smearedDirs)
    to.series.push_back({d + "/history.csv", "($9 > 0 ? $13 : 1/0):14", "", "smeared H = " + d.substr(9) + " mm", "lines dt 2"});
  io::renderPlot(to, dir / "traction_opening.png");
  io::PlotSpec ss;
  ss.title = "macro stress-strain of the enriched point (opening control): snap-back beyond h(E+E_p)/E_p";
  ss.xLabel = "eps_xx / (f_t'/E)";
  ss.yLabel = "sig_xx (MPa)";
  ss.logX = true;
  ss.xRange = "[0.5:]";
  const std::string scale = std::to_string(e / ft);
  for (size_t i = 0; i < enrichedDirs.size(); ++i)
    ss.series.push_back({enrichedDirs[i] + "/history.csv", "($3*" + scale + "):6", "",
                         "H = " + tag(result.rows[i].effectiveSize) + " mm", "lines lw 2"});
  io::renderPlot(ss, dir / "stress_strain.png");
  return result;
}

}  // namespace ecm::driver
