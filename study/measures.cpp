// ecm-study: the closed forms a run's errors are measured against (the fixed-free bar, the
// enriched point in uniaxial tension) and the measures of a run's curves (square wave, deviation).
#include <algorithm>
#include <cmath>
#include <functional>
#include <stdexcept>
#include <utility>
#include <vector>

#include "material/damage_function.hpp"
#include "material/uniaxial_closed_form.hpp"
#include "study/study.hpp"

namespace ecm::study {

BarVibration barVibrationClosedForm(const mpm::Scene& scene) {
  const mpm::Body* bar = nullptr;
  for (const mpm::Body& b : scene.bodies)
    if (!b.subtract && b.shape.kind == mpm::ShapeKind::Rectangle) {
      bar = &b;
      break;
    }
  if (!bar) throw std::invalid_argument("the scene has no rectangular body (the bar, along x)");
  const MaterialParams& m = scene.materials.at(static_cast<std::size_t>(bar->material));
  if (m.model != ModelKind::LinearElastic || m.elastic.poissonRatio != 0.0)
    throw std::invalid_argument("the bar's material must be linear_elastic with poisson_ratio 0 (a one-dimensional bar)");
  const double v0 = bar->initialVelocity[0];
  if (v0 == 0.0 || bar->initialVelocity[1] != 0.0)
    throw std::invalid_argument("the bar needs an initial velocity along x only");
  const double length = bar->shape.max[0] - bar->shape.min[0];
  const double area = (bar->shape.max[1] - bar->shape.min[1]) * scene.thickness;
  const double c = std::sqrt(m.elastic.youngsModulus / m.density);
  return {4.0 * length / c, m.density * c * std::abs(v0) * area};
}

SquareWave measureSquareWave(const std::vector<double>& t, const std::vector<double>& r, double amplitude) {
  SquareWave w;
  std::vector<double> crossings;
  int state = 0;
  double lastZero = NAN;
  for (std::size_t i = 1; i < t.size() && i < r.size(); ++i) {
    if ((r[i - 1] < 0.0) != (r[i] < 0.0) && r[i] != r[i - 1])
      lastZero = t[i - 1] + (t[i] - t[i - 1]) * r[i - 1] / (r[i - 1] - r[i]);
    const int now = r[i] > 0.5 * amplitude ? 1 : (r[i] < -0.5 * amplitude ? -1 : state);
    if (now != state) {
      if (state != 0 && std::isfinite(lastZero)) crossings.push_back(lastZero);
      state = now;
    }
  }
  w.crossings = static_cast<int>(crossings.size());
  if (crossings.empty()) return w;
  w.period = crossings.size() == 1 ? 2.0 * crossings[0]
                                   : 2.0 * (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
  double sum = 0.0;
  int count = 0;
  for (std::size_t i = 0; i < t.size() && i < r.size(); ++i) {
    const double phase = std::fmod(t[i] / (0.5 * w.period), 1.0);
    if (t[i] > 0.0 && phase >= 0.25 && phase <= 0.75) sum += std::abs(r[i]), ++count;
  }
  if (count > 0) w.amplitude = sum / count;
  return w;
}

UniaxialReference uniaxialTensionClosedForm(const MaterialParams& m, double bigH, double strainEnd) {
  const DamageLawParams law = m.band().law();
  const double e = m.elastic.youngsModulus, nu = m.elastic.poissonRatio, ft = m.tensileStrength, h = m.bandWidth;
  auto at = [&](double x) {
    const UniaxialBandPoint p = uniaxialBandResponse(law, nu, h, x);
    return std::pair{uniaxialMacroStrain(p, e, bigH), p.stress};
  };
  UniaxialReference ref;
  const double onset = ft / e;
  const int elastic = 50;
  for (int i = 0; i <= elastic; ++i) {
    const double eps = std::min(strainEnd, onset) * i / elastic;
    ref.strain.push_back(eps);
    ref.stress.push_back(e * eps);
  }
  ref.peakStress = e * std::min(strainEnd, onset);
  if (strainEnd <= onset) return ref;
  // The integrity at the end: eps(x) rises as x falls (below the snap-back size); bisection in ln x.
  const double xMin = 1e-15;
  double xEnd = xMin;
  if (at(xMin).first > strainEnd) {
    double lo = std::log(xMin), hi = 0.0;  // eps(lo) > strainEnd >= eps(hi)
    for (int it = 0; it < 200 && hi - lo > 1e-15; ++it) {
      const double mid = 0.5 * (lo + hi);
      (at(std::exp(mid)).first > strainEnd ? lo : hi) = mid;
    }
    xEnd = std::exp(0.5 * (lo + hi));
  }
  // Samples: damage D = 1 - x log-spaced from 1e-10 (the peak region), and x log-spaced (the tail).
  std::vector<double> xs;
  const int count = 800;
  for (int i = 0; i <= count; ++i) {
    const double d = std::exp(std::log(1e-10) + (std::log(1.0 - xEnd) - std::log(1e-10)) * i / count);
    xs.push_back(1.0 - d);
    xs.push_back(std::exp(std::log(xEnd) * i / count));
  }
  std::sort(xs.begin(), xs.end(), std::greater<>());
  xs.erase(std::unique(xs.begin(), xs.end()), xs.end());
  double previous = onset;
  std::vector<double> damage;  // D of each sample of the band branch
  for (const double x : xs) {
    if (x >= 1.0) continue;
    const auto [eps, sigma] = at(x);
    if (eps < previous - 1e-15 * onset)
      throw std::invalid_argument("the macro curve turns back (H beyond the snap-back size): no closed form as a function of strain");
    previous = eps;
    ref.strain.push_back(eps);
    ref.stress.push_back(sigma);
    damage.push_back(1.0 - x);
  }
  // The peak: the largest sample, refined by golden section in ln D between its neighbours.
  const std::size_t k = static_cast<std::size_t>(std::max_element(ref.stress.begin(), ref.stress.end()) - ref.stress.begin());
  ref.peakStress = ref.stress[k];
  const std::size_t first = elastic + 1;  // ref.stress[first + j] belongs to damage[j]
  if (k >= first && !damage.empty()) {
    const std::size_t j = k - first;
    auto stressAtLogD = [&](double u) { return at(1.0 - std::exp(u)).second; };
    double a = std::log(damage[j > 0 ? j - 1 : 0]), b = std::log(damage[std::min(j + 1, damage.size() - 1)]);
    const double g = 0.5 * (std::sqrt(5.0) - 1.0);
    double c = b - g * (b - a), d = a + g * (b - a);
    for (int it = 0; it < 200 && std::abs(b - a) > 1e-12; ++it) {
      if (stressAtLogD(c) > stressAtLogD(d)) b = d;
      else a = c;
      c = b - g * (b - a), d = a + g * (b - a);
    }
    ref.peakStress = std::max(ref.peakStress, stressAtLogD(0.5 * (a + b)));
  }
  ref.dissipation = h / bigH * dissipationBetween(law, 1.0, xEnd);
  return ref;
}

double maxDeviation(const std::vector<double>& x, const std::vector<double>& y, const std::vector<double>& cx,
                    const std::vector<double>& cy) {
  double worst = 0.0;
  if (cx.size() < 2) return NAN;
  std::size_t j = 1;
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (x[i] < cx.front() || x[i] > cx.back()) continue;
    if (j > 1 && cx[j - 1] > x[i]) j = 1;  // samples out of order: search from the start
    while (j + 1 < cx.size() && cx[j] < x[i]) ++j;
    const double span = cx[j] - cx[j - 1];
    const double s = span > 0.0 ? (x[i] - cx[j - 1]) / span : 1.0;
    worst = std::max(worst, std::abs(y[i] - (cy[j - 1] + s * (cy[j] - cy[j - 1]))));
  }
  return worst;
}

LoadCurve loadCurve(const io::CsvTable& h, const std::string& condition) {
  const auto column = [&](const std::string& name) {
    const auto at = std::find(h.header.begin(), h.header.end(), name) - h.header.begin();
    if (static_cast<std::size_t>(at) >= h.header.size()) throw std::runtime_error("no column " + name);
    return static_cast<std::size_t>(at);
  };
  const std::size_t ux = column(condition + "_ux_mm"), uy = column(condition + "_uy_mm");
  const std::size_t rx = column(condition + "_rx_N"), ry = column(condition + "_ry_N");
  const std::size_t dissipated = column("dissipated_Nmm");
  double most[2] = {0.0, 0.0};
  for (const auto& row : h.rows) most[0] = std::max(most[0], std::abs(row[ux])), most[1] = std::max(most[1], std::abs(row[uy]));
  const bool y = most[1] >= most[0];
  LoadCurve c;
  for (const auto& row : h.rows) {
    c.displacement.push_back(row[y ? uy : ux]);
    c.load.push_back(row[y ? ry : rx]);
    c.dissipated.push_back(row[dissipated]);
  }
  return c;
}

std::pair<double, double> dissipatedAtEqualDisplacement(const LoadCurve& run, const LoadCurve& ref) {
  if (run.displacement.size() < 2 || ref.displacement.size() < 2 || run.dissipated.size() != run.displacement.size() ||
      ref.dissipated.size() != ref.displacement.size())
    return {NAN, NAN};
  const double at = std::min(run.displacement.back(), ref.displacement.back());
  const auto interpolate = [at](const LoadCurve& c) {
    std::size_t j = 1;
    while (j + 1 < c.displacement.size() && c.displacement[j] < at) ++j;
    const double span = c.displacement[j] - c.displacement[j - 1];
    const double s = span > 0.0 ? std::clamp((at - c.displacement[j - 1]) / span, 0.0, 1.0) : 1.0;
    return c.dissipated[j - 1] + s * (c.dissipated[j] - c.dissipated[j - 1]);
  };
  return {interpolate(run), interpolate(ref)};
}

double postPeakCurveError(const LoadCurve& run, const LoadCurve& ref) {
  if (run.load.empty() || ref.load.empty()) return NAN;
  const auto peakAt = [](const LoadCurve& c) {
    return static_cast<std::size_t>(std::max_element(c.load.begin(), c.load.end()) - c.load.begin());
  };
  const std::size_t i = peakAt(run), j = peakAt(ref);
  const double from = std::max(run.displacement[i], ref.displacement[j]);
  const double to = std::min(run.displacement.back(), ref.displacement.back());
  if (!(to > from) || !(ref.load[j] > 0.0)) return NAN;
  // The branch of each curve between `from` and `to` (with the rows just outside, for interpolation).
  const auto branch = [&](const LoadCurve& c, std::size_t peak, std::vector<double>& x, std::vector<double>& y,
                          std::vector<double>& inside, std::vector<double>& insideY) {
    for (std::size_t k = peak; k < c.load.size(); ++k) {
      x.push_back(c.displacement[k]), y.push_back(c.load[k]);
      if (c.displacement[k] >= from && c.displacement[k] <= to) inside.push_back(c.displacement[k]), insideY.push_back(c.load[k]);
    }
  };
  std::vector<double> rx, ry, rin, riny, fx, fy, fin, finy;
  branch(run, i, rx, ry, rin, riny);
  branch(ref, j, fx, fy, fin, finy);
  const double worst = std::max(maxDeviation(rin, riny, fx, fy), maxDeviation(fin, finy, rx, ry));
  return worst / ref.load[j];
}

}  // namespace ecm::study
