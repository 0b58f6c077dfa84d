#include "mpm/scene/rve_sample.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>
#include <random>

namespace ecm::mpm {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kMaxInclusions = 1e6;  // a bound on the work of one sample

std::string fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

// Uniform in [0, 1) from the top 53 bits: the same on every standard library.
class Uniform {
 public:
  explicit Uniform(std::uint64_t seed) : engine_(seed) {}
  double operator()() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }
  double operator()(double lo, double hi) { return lo + (*this)() * (hi - lo); }

 private:
  std::mt19937_64 engine_;
};

// Buckets of placed inclusions on a uniform grid whose cells are at least as wide as the
// largest centre distance that can still conflict, so a query looks at 3 x 3 cells.
class Buckets {
 public:
  Buckets(const Vec2& origin, double side, double reach)
      : origin_(origin), n_(static_cast<int>(std::clamp(std::floor(side / reach), 1.0, 1024.0))), cell_(side / n_),
        cells_(static_cast<std::size_t>(n_) * static_cast<std::size_t>(n_)) {}

  template <class Conflict>
  bool anyNear(const Vec2& c, Conflict conflict) const {
    const int i = index(c[0] - origin_[0]), j = index(c[1] - origin_[1]);
    for (int jj = std::max(0, j - 1); jj <= std::min(n_ - 1, j + 1); ++jj)
      for (int ii = std::max(0, i - 1); ii <= std::min(n_ - 1, i + 1); ++ii)
        for (std::size_t k : cells_[at(ii, jj)])
          if (conflict(k)) return true;
    return false;
  }
  void add(const Vec2& c, std::size_t k) { cells_[at(index(c[0] - origin_[0]), index(c[1] - origin_[1]))].push_back(k); }

 private:
  Vec2 origin_;
  int n_;
  double cell_;
  std::vector<std::vector<std::size_t>> cells_;
  int index(double x) const { return std::clamp(static_cast<int>(std::floor(x / cell_)), 0, n_ - 1); }
  std::size_t at(int i, int j) const { return static_cast<std::size_t>(j) * static_cast<std::size_t>(n_) + static_cast<std::size_t>(i); }
};

}  // namespace

std::vector<GradingPoint> fullerGrading(double dMin, double dMax, double exponent, int classes) {
  if (!(dMin > 0.0 && dMax >= dMin)) throw std::invalid_argument("Fuller grading needs 0 < d_min <= d_max (mm)");
  if (!(exponent > 0.0)) throw std::invalid_argument("Fuller exponent must be > 0");
  if (classes < 1) throw std::invalid_argument("Fuller grading needs at least one class");
  if (dMax == dMin) return {{dMin, 0.0}, {dMax, 1.0}};  // one size
  std::vector<GradingPoint> g;
  for (int i = 0; i <= classes; ++i) {
    const double d = i == classes ? dMax : dMin * std::pow(dMax / dMin, static_cast<double>(i) / classes);
    g.push_back({d, std::pow(d / dMax, exponent)});
  }
  return g;
}

void RveParams::validate() const {
  if (!(side > 0.0 && std::isfinite(side))) throw std::invalid_argument("RVE side must be > 0 mm, got " + fmt(side));
  if (!(volumeFraction > 0.0 && volumeFraction < 1.0))
    throw std::invalid_argument("RVE volume fraction must be in (0, 1), got " + fmt(volumeFraction));
  if (grading.size() < 2) throw std::invalid_argument("RVE grading needs at least two (diameter, passing) points");
  if (!(grading.front().diameter > 0.0)) throw std::invalid_argument("RVE grading: diameters must be > 0 mm");
  for (std::size_t i = 1; i < grading.size(); ++i) {
    if (!(grading[i].diameter >= grading[i - 1].diameter))
      throw std::invalid_argument("RVE grading: diameters must not decrease (point " + std::to_string(i) + ")");
    if (!(grading[i].passing >= grading[i - 1].passing))
      throw std::invalid_argument("RVE grading: passing fractions must not decrease (point " + std::to_string(i) + ")");
  }
  if (!(grading.back().passing > grading.front().passing))
    throw std::invalid_argument("RVE grading: the passing fraction must increase from the first to the last point");
  if (!(itzThickness > 0.0)) throw std::invalid_argument("RVE ITZ thickness must be > 0 mm, got " + fmt(itzThickness));
  const double fit = maxDiameter() + 2.0 * itzThickness + 2.0 * effectiveGap();
  if (!(fit <= side))
    throw std::invalid_argument("RVE side " + fmt(side) + " mm cannot hold the largest inclusion with its ITZ and gap (" +
                                fmt(fit) + " mm)");
  const double most = volumeFraction * side * side / (0.25 * kPi * minDiameter() * minDiameter());
  if (most > kMaxInclusions)
    throw std::invalid_argument("RVE would need up to " + fmt(most) + " inclusions (at most " + fmt(kMaxInclusions) +
                                "): raise d_min or lower the side");
  if (attempts < 1) throw std::invalid_argument("RVE attempts must be >= 1");
  if (!(tolerance >= 0.0 && tolerance < 1.0)) throw std::invalid_argument("RVE tolerance must be in [0, 1)");
}

RveInfeasible::RveInfeasible(double t, double r, std::size_t placed)
    : std::runtime_error("RVE target inclusion fraction " + fmt(t) + " not reached: " + fmt(r) + " with " +
                         std::to_string(placed) + " inclusions (random sequential addition jammed; lower the "
                         "fraction, the ITZ thickness or the gap, or raise the attempts)"),
      target(t),
      reached(r) {}

RveSample generateRve(const RveParams& params) {
  params.validate();
  RveSample s;
  s.params = params;
  const double L = params.side, t = params.itzThickness, gap = params.effectiveGap();
  const double total = L * L;
  const double target = params.volumeFraction * total;
  Uniform uniform(params.seed);
  Buckets buckets(params.origin, L, params.maxDiameter() + 2.0 * t + gap);

  const auto& g = params.grading;
  const double p0 = g.front().passing, span = g.back().passing - p0;
  double placed = 0.0;     // inclusion area placed so far
  double allotted = 0.0;   // area assigned to the classes handled so far
  for (std::size_t c = g.size() - 1; c >= 1; --c) {
    const double lo = g[c - 1].diameter;
    double hi = g[c].diameter;
    allotted += target * (g[c].passing - g[c - 1].passing) / span;
    if (c == 1) allotted = target;  // no round-off left behind
    else if (g[c].passing == g[c - 1].passing) continue;  // an empty class: the carry goes further down
    // Rounds: draw the diameters that fill the class's remaining area, place them largest first;
    // what did not fit is drawn again (narrowed below the smallest miss) in the next round.
    for (int round = 0; round < 8; ++round) {
      std::vector<double> ds;
      for (double rem = allotted - placed;;) {
        const double dFit = std::sqrt(4.0 * std::max(rem, 0.0) / kPi);  // the circle that fills it exactly
        const double top = std::min(hi, dFit);
        if (top < lo) break;  // the rest goes to the finer classes
        ds.push_back(uniform(lo, top));
        rem -= 0.25 * kPi * ds.back() * ds.back();
      }
      if (ds.empty()) break;
      std::sort(ds.begin(), ds.end(), std::greater<>());
      std::size_t placedNow = 0;
      int misses = 0;
      for (std::size_t k = 0; k < ds.size() && misses < 3; ++k) {
        const double r = 0.5 * ds[k], reach = r + t + gap;  // centre bounds from the sides
        bool done = false;
        for (int a = 0; a < params.attempts && !done; ++a) {
          const Vec2 x(uniform(params.origin[0] + reach, params.origin[0] + L - reach),
                       uniform(params.origin[1] + reach, params.origin[1] + L - reach));
          const bool conflict = buckets.anyNear(x, [&](std::size_t j) {
            const Inclusion& o = s.inclusions[j];
            const double dmin = r + o.radius + 2.0 * t + gap;
            return (x - o.center).squaredNorm() < dmin * dmin;
          });
          if (conflict) continue;
          buckets.add(x, s.inclusions.size());
          s.inclusions.push_back({x, r});
          placed += kPi * r * r;
          done = true;
        }
        if (done) {
          ++placedNow;
          misses = 0;
        } else {
          ++misses;
          ++s.stats.dropped;
          hi = std::min(hi, ds[k]);  // larger ones will not fit either (most likely): narrow the class
        }
      }
      if (placedNow == 0) break;
    }
  }

  RveStats& st = s.stats;
  st.targetFraction = params.volumeFraction;
  st.count = s.inclusions.size();
  double itz = 0.0, sumD = 0.0;
  st.minDiameter = st.count ? 1e300 : 0.0;
  for (const Inclusion& i : s.inclusions) {
    itz += kPi * ((i.radius + t) * (i.radius + t) - i.radius * i.radius);
    sumD += 2.0 * i.radius;
    st.minDiameter = std::min(st.minDiameter, 2.0 * i.radius);
    st.maxDiameter = std::max(st.maxDiameter, 2.0 * i.radius);
  }
  st.achievedFraction = placed / total;
  st.itzFraction = itz / total;
  st.matrixFraction = 1.0 - st.achievedFraction - st.itzFraction;
  st.meanDiameter = st.count ? sumD / static_cast<double>(st.count) : 0.0;
  if (params.volumeFraction - st.achievedFraction > params.tolerance)
    throw RveInfeasible(params.volumeFraction, st.achievedFraction, st.count);
  return s;
}

std::vector<Body> rveBodies(const RveSample& sample, int matrix, int inclusion, int itz) {
  const RveParams& p = sample.params;
  std::vector<Body> bodies;
  bodies.reserve(1 + 2 * sample.inclusions.size());
  bodies.push_back({Shape::rectangle(p.origin, p.origin + Vec2(p.side, p.side)), matrix, false, Vec2::Zero()});
  for (const Inclusion& i : sample.inclusions)
    bodies.push_back({Shape::circle(i.center, i.radius + p.itzThickness), itz, false, Vec2::Zero()});
  for (const Inclusion& i : sample.inclusions) bodies.push_back({Shape::circle(i.center, i.radius), inclusion, false, Vec2::Zero()});
  return bodies;
}

}  // namespace ecm::mpm
