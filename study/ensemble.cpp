// ecm-study: RVE ensembles (samples: N). Each sample's strength (the peak mean stress) and the
// strain at it, and per mesh (every setting of the other knobs) the sample statistics, a Weibull
// fit, a histogram and a Weibull plot: ensemble_samples.csv, ensemble.csv, ensemble_histogram.png,
// weibull.png, and summary.json's "ensemble".
#include <gsl/gsl_cdf.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>

#include "io/atomic_file.hpp"
#include "io/gnuplot.hpp"
#include "study/internal.hpp"
#include "study/study.hpp"

namespace ecm::study {

using namespace detail;

SampleStatistics sampleStatistics(const std::vector<double>& x, double confidence) {
  SampleStatistics s;
  s.count = x.size();
  s.confidence = confidence;
  if (x.size() < 2) return s;
  const double n = static_cast<double>(x.size());
  s.mean = std::accumulate(x.begin(), x.end(), 0.0) / n;
  double squares = 0.0;
  for (const double v : x) squares += (v - s.mean) * (v - s.mean);
  s.stdDev = std::sqrt(squares / (n - 1.0));
  s.cov = s.stdDev / s.mean;
  const double alpha = 1.0 - confidence;
  const double t = gsl_cdf_tdist_Pinv(1.0 - alpha / 2.0, n - 1.0);
  s.meanLow = s.mean - t * s.stdDev / std::sqrt(n);
  s.meanHigh = s.mean + t * s.stdDev / std::sqrt(n);
  // McKay's interval, Vangel's modification: k / sqrt(((u + 2) / n - 1) k^2 + u / (n - 1)), u the
  // chi-square quantiles with n - 1 degrees (the upper one gives the lower bound).
  const auto bound = [&](double u) { return s.cov / std::sqrt(((u + 2.0) / n - 1.0) * s.cov * s.cov + u / (n - 1.0)); };
  s.covLow = bound(gsl_cdf_chisq_Pinv(1.0 - alpha / 2.0, n - 1.0));
  s.covHigh = bound(gsl_cdf_chisq_Pinv(alpha / 2.0, n - 1.0));
  // The mean within 1 % at this confidence: t(n - 1) cv / sqrt(n) <= 0.01, the cv taken as measured.
  long need = 2;
  while (need < 10000000 && gsl_cdf_tdist_Pinv(1.0 - alpha / 2.0, static_cast<double>(need - 1)) * std::abs(s.cov) /
                                    std::sqrt(static_cast<double>(need)) > 0.01)
    need = need < 1000 ? need + 1 : need + need / 100;
  s.samplesForOnePercent = need;
  return s;
}

WeibullFit fitWeibull(const std::vector<double>& values, double confidence) {
  WeibullFit w;
  w.confidence = confidence;
  std::vector<double> x = values;
  std::sort(x.begin(), x.end());
  if (x.size() < 2 || x.front() <= 0.0 || x.front() == x.back()) return w;
  const double n = static_cast<double>(x.size());
  std::vector<double> lx;
  for (const double v : x) lx.push_back(std::log(v));
  const double meanLog = std::accumulate(lx.begin(), lx.end(), 0.0) / n;
  // Maximum likelihood: g(m) = sum x^m ln x / sum x^m - 1/m - mean(ln x) = 0, increasing in m;
  // bisection on ln m (the powers scaled by the largest value, so they cannot overflow).
  const auto g = [&](double m) {
    double a = 0.0, b = 0.0;
    for (const double l : lx) {
      const double p = std::exp(m * (l - lx.back()));
      a += p * l;
      b += p;
    }
    return a / b - 1.0 / m - meanLog;
  };
  double lo = 1e-3, hi = 1e4;
  if (g(lo) > 0.0 || g(hi) < 0.0) return w;
  for (int i = 0; i < 200; ++i) {
    const double mid = std::sqrt(lo * hi);
    (g(mid) < 0.0 ? lo : hi) = mid;
  }
  w.modulus = std::sqrt(lo * hi);
  double sum = 0.0;
  for (const double l : lx) sum += std::exp(w.modulus * (l - lx.back()));
  w.scale = x.back() * std::pow(sum / n, 1.0 / w.modulus);
  // The Weibull plot: y_i = ln(-ln(1 - F_i)) against the fitted line y = m (ln x - ln scale).
  double mean = 0.0, total = 0.0, residual = 0.0, ks = 0.0;
  std::vector<double> y;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double rank = (static_cast<double>(i + 1) - 0.3) / (n + 0.4);
    y.push_back(std::log(-std::log(1.0 - rank)));
    mean += y.back() / n;
    const double fitted = 1.0 - std::exp(-std::pow(x[i] / w.scale, w.modulus));
    ks = std::max({ks, std::abs(fitted - static_cast<double>(i) / n), std::abs(fitted - static_cast<double>(i + 1) / n)});
  }
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double line = w.modulus * (lx[i] - std::log(w.scale));
    residual += (y[i] - line) * (y[i] - line);
    total += (y[i] - mean) * (y[i] - mean);
  }
  w.rSquared = 1.0 - residual / total;
  w.ksDistance = ks;
  // The inverse Fisher information of the two-parameter Weibull per sample: 6/pi^2 m^2 for m and
  // (pi^2/6 + (1 - gamma)^2) / (pi^2/6) scale^2 / m^2 for the scale (gamma: Euler's constant).
  const double z = gsl_cdf_ugaussian_Pinv(0.5 + 0.5 * confidence);
  const double piSquaredOver6 = M_PI * M_PI / 6.0, oneMinusGamma = 1.0 - 0.57721566490153286;
  const double modulusSpread = z * std::sqrt(1.0 / (piSquaredOver6 * n));
  const double scaleSpread = z * std::sqrt((piSquaredOver6 + oneMinusGamma * oneMinusGamma) / (piSquaredOver6 * n)) / w.modulus;
  w.modulusLow = w.modulus * std::exp(-modulusSpread);
  w.modulusHigh = w.modulus * std::exp(modulusSpread);
  w.scaleLow = w.scale * std::exp(-scaleSpread);
  w.scaleHigh = w.scale * std::exp(scaleSpread);
  return w;
}

namespace detail {

namespace {

struct Sample {
  int run = 0;
  std::string seed;
  double stress = NAN, strain = NAN;  // MPa, the peak mean stress, and the mean strain at it
};

struct Mesh {
  std::string label;  // the other knobs' values ("all" when the seed is the only knob)
  std::vector<Sample> samples;
  int failed = 0;
};

// The sample's strength from its run folder: the condition's largest |reaction| over the rows of
// history.csv (as the peak_reaction metric), over the sample's side x thickness; the strain is
// the condition's displacement at that row over the side.
Sample measureSample(const Study& study, const PlannedRun& p, const RunRecord& r, const std::filesystem::path& dir) {
  Sample s;
  s.run = r.id;
  s.seed = r.values.back();
  const YAML::Node root = io::parseYaml(p.sceneText, r.directory + "/scene.yaml").node();
  const auto side = findKeyPath(root, "bodies[0].rve.side");
  if (!side) throw std::runtime_error("samples: the scene's first body is not an rve: body with a side");
  const double length = side->as<double>();
  const LoadCurve c = loadCurve(io::readCsv(dir / r.directory / "history.csv"), study.condition);
  std::size_t peak = 0;
  for (std::size_t i = 0; i < c.load.size(); ++i)
    if (std::abs(c.load[i]) > std::abs(c.load[peak])) peak = i;
  if (c.load.empty()) return s;
  s.stress = std::abs(c.load[peak]) / (length * p.scene->thickness);
  s.strain = std::abs(c.displacement[peak]) / length;
  return s;
}

nlohmann::json statisticsJson(const SampleStatistics& s) {
  return {{"count", s.count},
          {"mean", jsonValue(s.mean)},
          {"std_dev", jsonValue(s.stdDev)},
          {"cov", jsonValue(s.cov)},
          {"confidence", s.confidence},
          {"mean_interval", {jsonValue(s.meanLow), jsonValue(s.meanHigh)}},
          {"cov_interval", {jsonValue(s.covLow), jsonValue(s.covHigh)}}};
}

std::string csvNumber(double v) { return std::isfinite(v) ? numberText(v) : ""; }

void plots(const Study& study, const std::vector<Mesh>& meshes, const std::vector<WeibullFit>& fits, const std::filesystem::path& dir) {
  // Histogram: bins of the pooled range (Sturges' count), one bar series per mesh.
  double lo = INFINITY, hi = -INFINITY;
  std::size_t most = 0;
  for (const Mesh& m : meshes) {
    most = std::max(most, m.samples.size());
    for (const Sample& s : m.samples) lo = std::min(lo, s.stress), hi = std::max(hi, s.stress);
  }
  if (!(hi > lo)) return;
  const int bins = static_cast<int>(std::ceil(std::log2(static_cast<double>(most)) + 1.0));
  const double width = (hi - lo) / bins;
  io::PlotSpec hist;
  hist.title = study.name + ": peak mean stress of the samples";
  hist.xLabel = "peak mean stress (MPa)";
  hist.yLabel = "samples";
  hist.yRange = "[0:*]";
  io::PlotSpec weibull;
  weibull.title = study.name + ": Weibull plot (points: median ranks; lines: maximum-likelihood fits)";
  weibull.xLabel = "ln(peak mean stress / MPa)";
  weibull.yLabel = "ln(-ln(1 - F))";
  std::string histText = "stress_MPa";
  for (std::size_t g = 0; g < meshes.size(); ++g) histText += ",mesh" + std::to_string(g + 1);
  histText += "\n";
  for (int b = 0; b < bins; ++b) {
    histText += numberText(lo + (b + 0.5) * width);
    for (const Mesh& m : meshes) {
      int count = 0;
      for (const Sample& s : m.samples) count += std::min(static_cast<int>((s.stress - lo) / width), bins - 1) == b;
      histText += "," + std::to_string(count);
    }
    histText += "\n";
  }
  io::writeFileAtomically(dir / "ensemble_histogram.csv", histText);
  if (most <= 10) hist.settings.push_back("set ytics 1");  // counts: whole numbers (gnuplot would tick 0.5)
  const double bar = width / static_cast<double>(meshes.size() + 1);
  const char* colours[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b"};
  for (std::size_t g = 0; g < meshes.size(); ++g) {
    const std::string colour = colours[g % 6];
    const std::string shift = numberText((static_cast<double>(g) - 0.5 * static_cast<double>(meshes.size() - 1)) * bar);
    hist.series.push_back({"ensemble_histogram.csv", "($1+" + shift + "):" + std::to_string(g + 2) + ":(" + numberText(bar) + ")",
                           "", meshes[g].label, "boxes fs solid 0.6 lc rgb '" + colour + "'"});
    std::string points = "ln_stress,ln_ln\n";
    std::vector<double> x;
    for (const Sample& s : meshes[g].samples) x.push_back(s.stress);
    std::sort(x.begin(), x.end());
    const double n = static_cast<double>(x.size());
    for (std::size_t i = 0; i < x.size(); ++i)
      points += numberText(std::log(x[i])) + "," + numberText(std::log(-std::log(1.0 - (static_cast<double>(i + 1) - 0.3) / (n + 0.4)))) + "\n";
    const std::string file = "weibull_mesh" + std::to_string(g + 1) + ".csv";
    io::writeFileAtomically(dir / file, points);
    weibull.series.push_back({file, "1:2", "", meshes[g].label, "points pt 7 ps 1.2 lc rgb '" + colour + "'"});
    if (std::isfinite(fits[g].modulus)) {
      const std::string f = "w" + std::to_string(g + 1);
      weibull.functions.push_back(f + "(x) = " + numberText(fits[g].modulus) + " * (x - " + numberText(std::log(fits[g].scale)) + ")");
      weibull.series.push_back({"", "", f + "(x)", "m = " + shortNumber(fits[g].modulus, 3) + ", scale " + shortNumber(fits[g].scale, 4) +
                                                       " MPa, R^2 " + shortNumber(fits[g].rSquared, 3),
                                "lines lw 2 lc rgb '" + colour + "'"});
    }
  }
  io::renderPlot(hist, dir / "ensemble_histogram.png");
  io::renderPlot(weibull, dir / "weibull.png");
}

}  // namespace

nlohmann::json writeEnsemble(const Study& study, const std::vector<PlannedRun>& plan, const StudyResult& result,
                             const std::filesystem::path& dir) {
  std::vector<Mesh> meshes;
  std::string samplesText = "mesh,run,seed,peak_mean_stress_MPa,strain_at_peak\n";
  for (std::size_t i = 0; i < plan.size(); ++i) {
    const RunRecord& r = result.runs[i];
    std::string label;
    for (std::size_t k = 0; k + 1 < study.knobs.size(); ++k) label += (label.empty() ? "" : " ") + study.knobs[k].key + "=" + r.values[k];
    if (label.empty()) label = "all";
    auto mesh = std::find_if(meshes.begin(), meshes.end(), [&](const Mesh& m) { return m.label == label; });
    if (mesh == meshes.end()) mesh = meshes.insert(meshes.end(), Mesh{label, {}, 0});
    Sample s;
    try {
      if (r.status == "completed") s = measureSample(study, plan[i], r, dir);
    } catch (const std::exception&) {
      s = Sample{};
    }
    if (!std::isfinite(s.stress)) {
      ++mesh->failed;
      continue;
    }
    mesh->samples.push_back(s);
    samplesText += std::to_string(mesh - meshes.begin() + 1) + "," + std::to_string(s.run) + "," + s.seed + "," + numberText(s.stress) + "," + numberText(s.strain) + "\n";
  }
  io::writeFileAtomically(dir / "ensemble_samples.csv", samplesText);
  std::string table = "mesh,samples,failed,stress_mean_MPa,stress_std_MPa,stress_cov,stress_mean_low,stress_mean_high,"
                      "stress_cov_low,stress_cov_high,samples_mean_within_1pct,strain_mean,strain_std,strain_cov,"
                      "weibull_modulus,weibull_scale_MPa,weibull_r2,weibull_ks,weibull_modulus_low,weibull_modulus_high,"
                      "weibull_scale_low_MPa,weibull_scale_high_MPa,label\n";
  nlohmann::json out = nlohmann::json::array();
  std::vector<WeibullFit> fits;
  for (const Mesh& m : meshes) {
    std::vector<double> stress, strain;
    for (const Sample& s : m.samples) stress.push_back(s.stress), strain.push_back(s.strain);
    const SampleStatistics a = sampleStatistics(stress), b = sampleStatistics(strain);
    const WeibullFit w = fitWeibull(stress);
    fits.push_back(w);
    // Cells appended, not built with "," + text: GCC 12 warns falsely (-Wrestrict) on the latter.
    const auto cell = [&](const std::string& text) { table.append(",").append(text); };
    table.append(std::to_string(fits.size()));
    cell(std::to_string(m.samples.size()));
    cell(std::to_string(m.failed));
    for (const double v : {a.mean, a.stdDev, a.cov, a.meanLow, a.meanHigh, a.covLow, a.covHigh}) cell(csvNumber(v));
    cell(a.samplesForOnePercent > 0 ? std::to_string(a.samplesForOnePercent) : std::string());
    for (const double v : {b.mean, b.stdDev, b.cov, w.modulus, w.scale, w.rSquared, w.ksDistance, w.modulusLow,
                           w.modulusHigh, w.scaleLow, w.scaleHigh})
      cell(csvNumber(v));
    table.append(",\"").append(m.label).append("\"\n");
    out.push_back({{"mesh", m.label},
                   {"index", fits.size()},
                   {"samples", m.samples.size()},
                   {"failed", m.failed},
                   {"peak_mean_stress_MPa", statisticsJson(a)},
                   {"samples_for_mean_within_1pct", a.samplesForOnePercent > 0 ? nlohmann::json(a.samplesForOnePercent) : nlohmann::json()},
                   {"strain_at_peak", statisticsJson(b)},
                   {"weibull", {{"modulus", jsonValue(w.modulus)}, {"scale_MPa", jsonValue(w.scale)},
                                {"confidence", w.confidence},
                                {"modulus_interval", {jsonValue(w.modulusLow), jsonValue(w.modulusHigh)}},
                                {"scale_interval_MPa", {jsonValue(w.scaleLow), jsonValue(w.scaleHigh)}},
                                {"r_squared", jsonValue(w.rSquared)}, {"ks_distance", jsonValue(w.ksDistance)},
                                {"fit", "maximum likelihood; intervals asymptotic (inverse Fisher information, on ln m and "
                                        "ln scale); r_squared on the Weibull plot with median ranks"}}}});
  }
  io::writeFileAtomically(dir / "ensemble.csv", table);
  plots(study, meshes, fits, dir);
  return {{"seed_knob", kSampleSeed},
          {"condition", study.condition},
          {"strength", "the condition's largest |reaction| over history.csv's rows / (rve side x thickness); strain: its "
                       "displacement at that row / side"},
          {"meshes", out}};
}

}  // namespace detail

std::string ensembleTable(const nlohmann::json& ensemble) {
  if (!ensemble.is_object() || !ensemble.contains("meshes")) return "";
  const auto number = [](const nlohmann::json& v, int digits) { return v.is_number() ? shortNumber(v.get<double>(), digits) : std::string("-"); };
  const auto interval = [&](const nlohmann::json& v, int digits) {
    if (!v.is_array() || v.size() != 2) return std::string("-");
    std::string text(1, '[');  // appended, not "[" + ...: GCC 12 warns falsely (-Wrestrict) on the latter
    text.append(number(v[0], digits)).append(", ").append(number(v[1], digits)).append("]");
    return text;
  };
  std::ostringstream out;
  double confidence = 0.95;
  for (const auto& m : ensemble["meshes"]) {
    const auto& s = m["peak_mean_stress_MPa"];
    const auto& w = m["weibull"];
    if (s.contains("confidence")) confidence = s["confidence"].get<double>();
    out << "  " << m["mesh"].get<std::string>() << ": " << m["samples"].get<int>() << " samples";
    if (m["failed"].get<int>() > 0) out << " (" << m["failed"].get<int>() << " failed)";
    out << "\n    strength mean " << number(s["mean"], 4) << " MPa " << interval(s["mean_interval"], 4) << ", CV "
        << number(s["cov"], 3) << " " << interval(s["cov_interval"], 3) << "\n    Weibull modulus " << number(w["modulus"], 3)
        << " " << interval(w["modulus_interval"], 3) << ", scale " << number(w["scale_MPa"], 4) << " MPa "
        << interval(w["scale_interval_MPa"], 4) << "\n";
  }
  std::string head("ensemble (intervals at ");
  head.append(shortNumber(100.0 * confidence, 3)).append(" % confidence):\n");
  return head + out.str();
}

}  // namespace ecm::study
